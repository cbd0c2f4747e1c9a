#pragma once
// The files of an elastic analysis: fields.h5/.xmf, history.csv, line_*.csv and summary.json.
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::implicit {

/// Writes fields.h5/.xmf, history.csv, line_*.csv and summary.json (rank 0).
void write_elastic_outputs(const spec::ProblemSpec& spec, const ElasticResult& r,
                           const solvers::PetscSession& session, io::OutputDirectory& out);

} // namespace mf::implicit
