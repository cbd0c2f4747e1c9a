#pragma once
// The plane analyses' problems refined as discretisation.adapt asks, with their own pilots: an
// elastic solve, or the elastoplastic schedule in at most pilot_increments increments a step,
// neither writing output.
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/solvers/petsc_session.hpp"

namespace mf::implicit {

AdaptedProblem adapted_elastic(const spec::ProblemSpec& spec, const solvers::PetscSession& session);
AdaptedProblem adapted_elastoplastic(const spec::ProblemSpec& spec,
                                     const solvers::PetscSession& session);

} // namespace mf::implicit
