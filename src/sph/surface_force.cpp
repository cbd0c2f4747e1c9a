#include "meshfree/sph/surface_force.hpp"
#include "meshfree/sph/hydro.hpp"
#include <algorithm>

namespace mf::sph {

std::unique_ptr<Condition> SurfaceForce::clone() const {
  return std::make_unique<SurfaceForce>(*this);
}

void SurfaceForce::add_accelerations(const Hydro& s, double, std::vector<double>& dv) const {
  const particles::ParticleSet& P = s.particles;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const int i = particles[k];
    if (s.fields.fixed[i]) continue;
    for (int d = 0; d < 3; ++d) dv[3 * i + d] += force[3 * k + d] / P.mass[i];
  }
}

void SurfaceForce::append_forces(const Hydro& s, double, std::vector<int>& who,
                                 std::vector<double>& out) const {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const int i = particles[k];
    if (s.fields.fixed[i]) continue;
    who.push_back(i);
    for (int d = 0; d < 3; ++d) out.push_back(force[3 * k + d]);
  }
}

std::unique_ptr<Condition> SurfaceForce::owned_part(const particles::ParticleSet& P) const {
  const OwnedEntries mine = owned_entries(P, particles);
  auto out = std::make_unique<SurfaceForce>();
  out->name = name;
  out->particles = mine.local;
  out->force = pick(force, mine.entries, 3);
  return out;
}

double SurfaceForce::largest_held_force() const {
  double f = 0.0;
  for (std::size_t k = 0; k < particles.size(); ++k)
    f = std::max(f, Vec3(force[3 * k], force[3 * k + 1], force[3 * k + 2]).norm());
  return f;
}

} // namespace mf::sph
