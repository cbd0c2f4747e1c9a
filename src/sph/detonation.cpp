#include "meshfree/sph/detonation.hpp"
#include <cmath>
#include <variant>

namespace mf::sph {

namespace {
/// Lights every explosive particle at distance(x) / D_CJ; with an unreacted equation of state
/// only a booster of 2 h is lit on schedule, and the shock lights the rest (update_state).
template <class Distance> void light_by_distance(Hydro& s, Distance distance) {
  group_materials(s);
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const auto* explosive = std::get_if<materials::JwlExplosive>(&s.materials[m].eos);
    if (!explosive) continue;
    const int* members = s.groups.of(m);
    for (int k = 0; k < s.groups.count(m); ++k) {
      const int i = members[k];
      const Vec3 x = P.position(i);
      const double r = distance(x.data());
      if (explosive->unreacted && r > 2.0 * F.h[i]) continue;
      F.light_time[i] = r / explosive->jwl.detonation_speed;
    }
  }
}
} // namespace

void light_from_point(Hydro& s, const double at[3]) {
  light_by_distance(s, [at](const double* x) {
    return std::sqrt((x[0] - at[0]) * (x[0] - at[0]) + (x[1] - at[1]) * (x[1] - at[1]) +
                     (x[2] - at[2]) * (x[2] - at[2]));
  });
}

void light_from_plane(Hydro& s, const double at[3], const double normal[3]) {
  light_by_distance(s, [at, normal](const double* x) {
    return std::abs((x[0] - at[0]) * normal[0] + (x[1] - at[1]) * normal[1] +
                    (x[2] - at[2]) * normal[2]);
  });
}

} // namespace mf::sph
