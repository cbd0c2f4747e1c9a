#pragma once
// Quasi-static elastoplastic analysis (J2, plane stress or plane strain, small strain) on the
// same Galerkin model as the elastic solver, meshfree or finite elements: first yield from an
// elastic solve, then the load schedule, each increment solved by Newton through PETSc SNES with
// the consistent tangent (see elastoplastic_system.hpp and load_stepping.hpp).
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::implicit {

/// Runs the load schedule. Fields go to `out` (rank 0; null on other ranks or to skip them) as
/// the run goes. A run whose increment cannot converge even after the allowed cut-backs stops
/// with status "stopped", keeping the converged increments; the returned state is the last
/// converged one either way. After every converged increment but the last a checkpoint goes to
/// `dir`/checkpoint (empty: none): the nodal parameters, every Gauss point's committed history
/// and the trial response kept with it, the load factors and the schedule's position, and the
/// increments recorded; with `restart` the schedule goes on from that checkpoint.
ElastoplasticResult solve_elastoplastic_static(const spec::ProblemSpec& spec,
                                               const solvers::PetscSession& session,
                                               io::OutputDirectory* out,
                                               const std::string& dir = {},
                                               const io::Restart* restart = nullptr);

} // namespace mf::implicit
