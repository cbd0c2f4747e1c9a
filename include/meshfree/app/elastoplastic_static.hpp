#pragma once
// Quasi-static elastoplastic analysis (J2, plane stress or plane strain) on a Galerkin model.
#include "meshfree/app/analysis.hpp"
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::app {

/// Builds the model, runs the load schedule (fields written as it goes), and writes the history
/// and summary to `out` (rank 0; null elsewhere). The result holds the converged state.
/// Checkpoints go to `dir`/checkpoint (empty: none); `restart` continues from one. The result
/// keeps the record of the refinement that made the problem's cloud, if it was adapted.
implicit::ElastoplasticResult elastoplastic_static(const implicit::AdaptedProblem& problem,
                                                   const solvers::PetscSession& session,
                                                   io::OutputDirectory* out,
                                                   const std::string& dir = {},
                                                   const io::Restart* restart = nullptr);

/// The table entry of `analysis: elastoplastic_static`.
AnalysisEntry elastoplastic_static_entry();

} // namespace mf::app
