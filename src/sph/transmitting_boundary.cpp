#include "meshfree/sph/transmitting_boundary.hpp"
#include "meshfree/sph/hydro.hpp"
#include <algorithm>

namespace mf::sph {

void TransmittingBoundary::force_on(std::size_t k, const double* v, double f[3]) const {
  const double vn = v[0] * normal[0] + v[1] * normal[1] + v[2] * normal[2];
  for (int d = 0; d < 3; ++d) {
    const double normal_part = vn * normal[d];
    f[d] =
        -area[k] * (normal_impedance[k] * normal_part + shear_impedance[k] * (v[d] - normal_part));
  }
  if (!static_force.empty())
    for (int d = 0; d < 3; ++d) f[d] += static_force[3 * k + d];
}

std::unique_ptr<Condition> TransmittingBoundary::clone() const {
  return std::make_unique<TransmittingBoundary>(*this);
}

void TransmittingBoundary::add_accelerations(const Hydro& s, double,
                                             std::vector<double>& dv) const {
  const particles::ParticleSet& P = s.particles;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const int i = particles[k];
    double f[3];
    force_on(k, &P.v[3 * static_cast<std::size_t>(i)], f);
    for (int d = 0; d < 3; ++d) dv[3 * i + d] += f[d] / P.mass[i];
  }
}

void TransmittingBoundary::append_forces(const Hydro& s, double, std::vector<int>& who,
                                         std::vector<double>& force) const {
  const particles::ParticleSet& P = s.particles;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    double f[3];
    force_on(k, &P.v[3 * static_cast<std::size_t>(particles[k])], f);
    who.push_back(particles[k]);
    for (int d = 0; d < 3; ++d) force.push_back(f[d]);
  }
}

std::unique_ptr<Condition> TransmittingBoundary::owned_part(const particles::ParticleSet& P) const {
  const OwnedEntries mine = owned_entries(P, particles);
  auto out = std::make_unique<TransmittingBoundary>(*this);
  out->particles = mine.local;
  out->area = pick(area, mine.entries);
  out->normal_impedance = pick(normal_impedance, mine.entries);
  out->shear_impedance = pick(shear_impedance, mine.entries);
  if (!static_force.empty()) out->static_force = pick(static_force, mine.entries, 3);
  return out;
}

double TransmittingBoundary::largest_held_force() const {
  double f = 0.0;
  for (std::size_t k = 0; k < static_force.size() / 3; ++k)
    f = std::max(
        f, Vec3(static_force[3 * k], static_force[3 * k + 1], static_force[3 * k + 2]).norm());
  return f;
}

} // namespace mf::sph
