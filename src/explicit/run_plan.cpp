#include "meshfree/explicit/run_plan.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/sph/step.hpp"
#include <cmath>

namespace mf::explicit_dynamics {

void print_pd_plan(const spec::ProblemSpec& spec, std::ostream& os) {
  PhaseTimer timer;
  const PdSetup setup = build_pd_setup(spec, timer);
  require_finite_run(planned_run(spec.pd(), setup), "out/" + spec.name);
  os << "  peridynamics: " << setup.model.particles.size() << " particles, "
     << setup.model.bonds.pairs() << " bonds, horizon " << setup.model.horizon << "\n  time step "
     << setup.dt << " (" << setup.dt_limit << "), "
     << static_cast<long>(std::ceil(spec.pd().end_time / setup.dt)) << " steps\n"
     << "  memory: "
     << describe_bytes(bytes_per::pd_particle * setup.model.particles.size() +
                       bytes_per::pd_partner * setup.model.bonds.directed)
     << " for the discretisation, besides " << describe_bytes(bytes_per::program)
     << " for the program\n";
}

void print_sph_plan(const spec::ProblemSpec& spec, std::ostream& os) {
  const sph::Hydro h = build_sph(spec.sph());
  int limiting = -1;
  const double dt = sph::stable_step(h, &limiting);
  require_finite_run(planned_run(spec.sph(), h.particles.size(), dt), "out/" + spec.name);
  os << "  sph: " << h.particles.size() << " particles in " << spec.sph().dimension
     << "D, first CFL step " << dt << " (particle " << limiting << "), about "
     << static_cast<long>(std::ceil(spec.sph().end_time / dt)) << " steps or more\n"
     << "  memory: "
     << describe_bytes(h.particles.size() * bytes_per::sph_particle(spec.sph().dimension))
     << " for the discretisation, besides " << describe_bytes(bytes_per::program)
     << " for the program\n";
}

void require_finite_pd_run(const spec::ProblemSpec& spec, const std::string& folder) {
  PhaseTimer timer;
  const auto setup = build_pd_setup(spec, timer);
  refuse_endless_run(planned_run(spec.pd(), setup), folder);
}

void require_finite_sph_run(const spec::ProblemSpec& spec, const std::string& folder) {
  const sph::Hydro h = build_sph(spec.sph());
  refuse_endless_run(planned_run(spec.sph(), h.particles.size(), sph::stable_step(h)), folder);
}

} // namespace mf::explicit_dynamics
