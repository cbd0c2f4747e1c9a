#pragma once
// Quasi-static elastoplastic analysis (J2, plane stress or plane strain) on a Galerkin model.
#include "meshfree/app/analysis.hpp"
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <optional>

namespace mf::app {

/// Builds the model, runs the load schedule (fields written as it goes), and writes the history
/// and summary to `out` (rank 0; null elsewhere). The result holds the converged state.
/// Checkpoints go to `dir`/checkpoint (empty: none); `restart` continues from one. `adaptation`
/// is the record of the refinement that made the spec's cloud, if it was adapted.
implicit::ElastoplasticResult
elastoplastic_static(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                     io::OutputDirectory* out, const std::string& dir = {},
                     const io::Restart* restart = nullptr,
                     std::optional<implicit::Adaptation> adaptation = {});

/// An elastoplastic schedule's increments bounded by the time a run may take here and by the disk
/// of `folder`; the step whose increments pass a bound is named.
void require_increment_output(const spec::ProblemSpec& spec, const std::string& folder);

/// The table entry of `analysis: elastoplastic_static`.
AnalysisEntry elastoplastic_static_entry();

} // namespace mf::app
