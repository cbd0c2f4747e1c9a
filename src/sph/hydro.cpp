#include "meshfree/sph/hydro.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>

namespace mf::sph {

bool Hydro::any_solid() const {
  return std::any_of(materials.begin(), materials.end(),
                     [](const Material& m) { return m.solid(); });
}

int add_particle(Hydro& s, const Vec3& x, double volume, double density, double e, double h,
                 int material, bool fixed) {
  s.fields.add(density, e, h, fixed);
  return s.particles.add(x, volume, density, material);
}

void group_materials(Hydro& s, bool force) {
  const particles::ParticleSet& P = s.particles;
  MaterialGroups& g = s.groups;
  if (!force && g.built_for == P.size()) return;
  const std::size_t count = s.materials.size();
  const int owned = P.owned_count();
  g.start.assign(count + 1, 0);
  g.owned_end.assign(count, 0);
  for (const int i : P.all()) {
    if (P.material[i] < 0 || P.material[i] >= static_cast<int>(count))
      fail("SPH: particle ", i, " has material ", P.material[i], " of ", count);
    ++g.start[P.material[i] + 1];
  }
  for (std::size_t m = 0; m < count; ++m) g.start[m + 1] += g.start[m];
  g.members.resize(P.size());
  std::vector<int> next(g.start.begin(), g.start.end() - 1);
  // Ascending within each material: owned particles come before the ghosts.
  for (const int i : P.all()) {
    const std::size_t m = static_cast<std::size_t>(P.material[i]);
    g.members[next[m]++] = i;
    if (i < owned) g.owned_end[m] = next[m];
  }
  for (std::size_t m = 0; m < count; ++m) g.owned_end[m] = std::max(g.owned_end[m], g.start[m]);
  g.built_for = P.size();
}

} // namespace mf::sph
