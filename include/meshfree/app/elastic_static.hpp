#pragma once
// Linear elastic static analysis on a Galerkin model (meshfree RK/MLS or finite elements).
#include "meshfree/app/analysis.hpp"
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::app {

/// Builds the model, solves K d = f, and writes the results to `out` (rank 0; null elsewhere),
/// with the record of the refinement that made the problem's cloud, if it was adapted.
implicit::ElasticResult elastic_static(const implicit::AdaptedProblem& problem,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory* out);

/// What `check` prints of a Galerkin analysis (elastic or elastoplastic): method, nodes or mesh,
/// integration points, memory, the boundary conditions and the steps.
void describe_galerkin(const spec::ProblemSpec& spec);

/// A finite-element mesh is input too: read and checked before anything is written.
void admit_galerkin(const spec::ProblemSpec& spec, const std::string& folder);

/// The table entry of `analysis: elastic_static`.
AnalysisEntry elastic_static_entry();

} // namespace mf::app
