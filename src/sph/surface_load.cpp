#include "meshfree/sph/surface_load.hpp"
#include "meshfree/sph/hydro.hpp"

namespace mf::sph {

std::unique_ptr<Condition> SurfaceLoad::clone() const {
  return std::make_unique<SurfaceLoad>(*this);
}

void SurfaceLoad::add_accelerations(const Hydro& s, double t, std::vector<double>& dv) const {
  const particles::ParticleSet& P = s.particles;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const int i = particles[k];
    if (s.fields.fixed[i]) continue;
    const double f = pulses[k](t) * area[k] / P.mass[i];
    for (int d = 0; d < 3; ++d) dv[3 * i + d] += f * direction[d];
  }
}

void SurfaceLoad::append_forces(const Hydro& s, double t, std::vector<int>& who,
                                std::vector<double>& force) const {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const int i = particles[k];
    if (s.fields.fixed[i]) continue;
    const double f = pulses[k](t) * area[k];
    who.push_back(i);
    for (int d = 0; d < 3; ++d) force.push_back(f * direction[d]);
  }
}

std::unique_ptr<Condition> SurfaceLoad::owned_part(const particles::ParticleSet& P) const {
  const OwnedEntries mine = owned_entries(P, particles);
  auto out = std::make_unique<SurfaceLoad>(*this);
  out->particles = mine.local;
  out->area = pick(area, mine.entries);
  out->pulses = pick(pulses, mine.entries);
  return out;
}

} // namespace mf::sph
