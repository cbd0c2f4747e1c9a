#pragma once
// The files of an elastoplastic analysis besides its field series: history.csv (one row per
// converged increment), line_*.csv and summary.json.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::implicit {

/// Writes history.csv, line_*.csv and summary.json (rank 0).
void write_elastoplastic_outputs(const spec::ProblemSpec& spec, const ElastoplasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out);

} // namespace mf::implicit
