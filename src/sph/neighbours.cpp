#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <cmath>

namespace mf::sph {

void refresh_neighbours(Hydro& s) {
  group_materials(s);
  const Particles& P = s.particles;
  const int n = P.size();
  const double skin = s.settings.skin;
  // A pair (i, j) left out at the last build was at least (h_i + h_j)(1 + skin) apart then; it
  // cannot interact yet while every particle has moved and grown its h by less than skin h.
  if (!s.x_at_build.empty()) {
    bool stale = false;
#pragma omp parallel for schedule(static) reduction(|| : stale)
    for (int i = 0; i < n; ++i) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double dx = P.x[3 * i + k] - s.x_at_build[3 * i + k];
        d2 += dx * dx;
      }
      const double grown = std::max(0.0, P.h[i] - s.h_at_build[i]);
      if (std::sqrt(d2) + grown > skin * s.h_at_build[i]) stale = true;
    }
    if (!stale) return;
  }
  const double h_max = *std::max_element(P.h.begin(), P.h.begin() + s.real_count());
  s.build_radius = 2.0 * h_max * (1.0 + skin);
  if (!s.symmetry.empty()) rebuild_ghosts(s, s.build_radius);
  const neighbors::PairList all = neighbors::pairs_within(P.x, s.build_radius);
  // Keep the pairs within (h_i + h_j)(1 + skin): with smoothing lengths that differ across the
  // body, the global radius would hand small particles many far partners.
  const int with_ghosts = P.size();
  s.pairs.offset.assign(with_ghosts + 1, 0);
  s.pairs.partner.clear();
  for (int i = 0; i < with_ghosts; ++i) {
    for (long k = all.offset[i]; k < all.offset[i + 1]; ++k) {
      const int j = all.partner[k];
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double dx = P.x[3 * i + d] - P.x[3 * j + d];
        r2 += dx * dx;
      }
      const double reach = (P.h[i] + P.h[j]) * (1.0 + skin);
      if (r2 < reach * reach) s.pairs.partner.push_back(j);
    }
    s.pairs.offset[i + 1] = static_cast<long>(s.pairs.partner.size());
  }
  s.x_at_build = P.x;
  s.h_at_build = P.h;
  ++s.rebuilds;
}

} // namespace mf::sph
