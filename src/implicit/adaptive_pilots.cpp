#include "meshfree/implicit/adaptive_pilots.hpp"
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"

namespace mf::implicit {

AdaptedProblem adapted_elastic(const spec::ProblemSpec& spec,
                               const solvers::PetscSession& session) {
  return adapted_problem(
      spec, [&](const spec::ProblemSpec& s) { return solve_elastic_static(s, session).estimate; });
}

AdaptedProblem adapted_elastoplastic(const spec::ProblemSpec& spec,
                                     const solvers::PetscSession& session) {
  return adapted_problem(spec, [&](const spec::ProblemSpec& s) {
    return solve_elastoplastic_static(pilot_spec(s), session, nullptr).estimate;
  });
}

} // namespace mf::implicit
