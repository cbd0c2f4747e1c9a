#include "meshfree/explicit/surface_blast.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>

namespace mf::explicit_dynamics {

std::vector<loads::Friedlander> surface_pulses(const Charge& charge,
                                               const std::vector<double>& positions,
                                               const std::vector<int>& particles,
                                               const std::string& key_path) {
  const loads::Burst burst =
      charge.surface_burst ? loads::Burst::HemisphericalSurface : loads::Burst::SphericalFreeAir;
  const double r_min = loads::kingery_bulmash_range(burst).first * std::cbrt(charge.tnt_mass);
  std::vector<loads::Friedlander> out;
  out.reserve(particles.size());
  for (int i : particles) {
    const Vec3 x(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    const Vec3 ray = x - charge.center;
    const double r = ray.norm();
    loads::BlastParameters b;
    try {
      b = loads::kingery_bulmash(burst, charge.tnt_mass,
                                 charge.clamp_below_range ? std::max(r, r_min) : r);
    } catch (const Error& e) {
      fail(key_path, ".blast: particle at (", x.x(), ", ", x.y(), ", ", x.z(), "): ", e.what());
    }
    out.push_back(loads::blast_pulse(b, -charge.normal.dot(ray) / r));
  }
  return out;
}

} // namespace mf::explicit_dynamics
