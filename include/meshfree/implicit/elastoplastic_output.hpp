#pragma once
// The files of an elastoplastic analysis besides its field series: history.csv (one row per
// converged increment), line_*.csv and summary.json.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/solvers/petsc_session.hpp"

namespace mf::implicit {

/// Writes history.csv, line_*.csv and summary.json (rank 0).
void write_elastoplastic_outputs(const io::ProblemSpec& spec, const ElastoplasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out);

} // namespace mf::implicit
