#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace mf::sph {

void refresh_neighbours(Hydro& s) {
  group_materials(s);
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
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
        const double dx = P.X[3 * i + k] + P.u[3 * i + k] - s.x_at_build[3 * i + k];
        d2 += dx * dx;
      }
      const double grown = std::max(0.0, F.h[i] - s.h_at_build[i]);
      if (std::sqrt(d2) + grown > skin * s.h_at_build[i]) stale = true;
    }
    if (!stale) return;
  }
  const double h_max = *std::max_element(F.h.begin(), F.h.begin() + P.owned_count());
  s.build_radius = 2.0 * h_max * (1.0 + skin);
  if (!s.symmetry.empty()) rebuild_ghosts(s, s.build_radius);
  std::vector<double> x(P.X.size()); // current positions X + u, ghosts included
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = P.X[k] + P.u[k];
  const neighbors::PairList all = neighbors::pairs_within(x, s.build_radius);
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
        const double dx = x[3 * i + d] - x[3 * j + d];
        r2 += dx * dx;
      }
      const double reach = (F.h[i] + F.h[j]) * (1.0 + skin);
      if (r2 < reach * reach) s.pairs.partner.push_back(j);
    }
    s.pairs.offset[i + 1] = static_cast<long>(s.pairs.partner.size());
  }
  s.x_at_build = std::move(x);
  s.h_at_build = F.h;
  ++s.rebuilds;
}

} // namespace mf::sph
