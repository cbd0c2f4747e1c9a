#include "meshfree/explicit/run_plan.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/geometry/lattice.hpp"
#include "meshfree/sph/step.hpp"
#include <cmath>
#include <utility>

namespace mf::explicit_dynamics {

namespace {

/// Bonds that `check` builds to report a body exactly: beyond them (about 2 million particles at
/// a horizon of 3 spacings in 3D) building them takes longer than checking an input should
/// (5 s a million particles on two threads), so `check` reports estimates from the lattice and
/// the run builds and checks the rest.
constexpr double kCheckedBondsAtMost = 2.5e8;

/// The particles of the lattice over the body's box and their bond partners, before they exist.
std::pair<double, double> pd_estimate(const spec::ProblemSpec& spec) {
  const spec::PdSpec& s = spec.pd();
  const bool solid = s.dimension == materials::PdDimension::Solid3D;
  const Vec3 lo =
      solid ? spec.box->lo : Vec3(spec.domain.bounds().lo.x(), spec.domain.bounds().lo.y(), 0.0);
  const Vec3 hi =
      solid ? spec.box->hi : Vec3(spec.domain.bounds().hi.x(), spec.domain.bounds().hi.y(), 0.0);
  const double particles =
      geometry::Lattice::of_spacing(lo, hi, s.spacing, solid ? 3 : 2).cells_total();
  const double m = s.horizon_factor;
  const double partners = solid ? 4.0 / 3.0 * M_PI * m * m * m : M_PI * m * m;
  return {particles, particles * partners};
}

} // namespace

void print_pd_plan(const spec::ProblemSpec& spec, std::ostream& os) {
  const auto [particles, directed] = pd_estimate(spec);
  if (directed > kCheckedBondsAtMost) {
    require_memory("discretisation.spacing", "particles in the body", particles,
                   bytes_per::pd_particle + bytes_per::pd_partner * directed / particles);
    os << "  peridynamics: about " << particles << " particles (the lattice over the body's box), "
       << "about " << directed / 2.0 << " bonds: too many to build for a check; the run builds "
       << "them (about " << std::lround(5e-6 * particles)
       << " s) and then checks its time step and "
       << "bounds\n  memory: "
       << describe_bytes(bytes_per::pd_particle * particles + bytes_per::pd_partner * directed)
       << " for the discretisation, besides " << describe_bytes(bytes_per::program)
       << " for the program\n";
    return;
  }
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
  require_finite_run(planned_run(spec.sph(), h), "out/" + spec.name);
  double volume = 0.0;
  for (const double v : h.particles.volume) volume += v;
  os << "  sph: " << h.particles.size() << " particles in " << spec.sph().dimension
     << "D of volume " << volume << ", first CFL step " << dt << " (particle " << limiting
     << "), about " << static_cast<long>(std::ceil(spec.sph().end_time / dt)) << " steps or more\n"
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
  refuse_endless_run(planned_run(spec.sph(), h), folder);
}

} // namespace mf::explicit_dynamics
