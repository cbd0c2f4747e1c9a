#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"

namespace mf::app {

implicit::ElastoplasticResult elastoplastic_static(const io::ProblemSpec& spec,
                                                   const solvers::PetscSession& session,
                                                   io::OutputDirectory* out, const std::string& dir,
                                                   const io::Restart* restart) {
  implicit::ElastoplasticResult r =
      implicit::solve_elastoplastic_static(spec, session, out, dir, restart);
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) implicit::write_elastoplastic_outputs(spec, r, session, *out);
  }
  return r;
}

} // namespace mf::app
