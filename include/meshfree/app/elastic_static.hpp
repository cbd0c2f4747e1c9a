#pragma once
// Linear elastic static analysis on a Galerkin model (meshfree RK/MLS or finite elements).
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/solvers/petsc_session.hpp"

namespace mf::app {

/// Builds the model, solves K d = f, and writes the results to `out` (rank 0; null elsewhere).
implicit::ElasticResult elastic_static(const io::ProblemSpec& spec,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory* out);

} // namespace mf::app
