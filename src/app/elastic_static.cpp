#include "meshfree/app/elastic_static.hpp"
#include "meshfree/implicit/elastic_output.hpp"

namespace mf::app {

implicit::ElasticResult elastic_static(const io::ProblemSpec& spec,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory* out) {
  // The display mesh on every rank alike (its nodal average is collective; `out` is rank 0's).
  implicit::ElasticResult r = implicit::solve_elastic_static(spec, session, true);
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) implicit::write_elastic_outputs(spec, r, session, *out);
  }
  return r;
}

} // namespace mf::app
