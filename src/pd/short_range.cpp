#include "meshfree/pd/short_range.hpp"
#include <algorithm>
#include <cmath>

namespace mf::pd {

ShortRangeContact::ShortRangeContact(const Model& m, double skin)
    : reach_(1.35 * m.spacing), skin_(skin * m.spacing) {}

void ShortRangeContact::rebuild(const std::vector<double>& y) {
  pairs_ = neighbors::pairs_within(y, reach_ + skin_);
  y_built_ = y;
  ++rebuilds_;
}

double ShortRangeContact::add_forces(const Model& m, const std::vector<double>& y,
                                     std::vector<double>& force) {
  const particles::ParticleSet& p = m.particles;
  const int n = p.owned_count();
  // A pair outside the list was farther apart than reach + skin at the build; it cannot be
  // within reach >= d_ij while no particle has moved more than skin / 2.
  bool stale = y_built_.size() != y.size();
  if (!stale) {
    double moved = 0.0;
#pragma omp parallel for schedule(static) reduction(max : moved)
    for (int i = 0; i < n; ++i) {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double e = y[3 * i + d] - y_built_[3 * i + d];
        d2 += e * e;
      }
      moved = std::max(moved, d2);
    }
    stale = 4.0 * moved > skin_ * skin_;
  }
  if (stale) rebuild(y);
  const int materials = static_cast<int>(m.material_names.size());
  const double lc = m.spacing, delta = m.horizon;
  double energy = 0.0;
  // Each pair is in both rows; row i gives i its own force (no write to j, no atomics) and half
  // of the pair's energy.
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : energy)
  for (int i = 0; i < n; ++i) {
    double fx = 0.0, fy = 0.0, fz = 0.0, e = 0.0;
    for (long k = pairs_.offset[i]; k < pairs_.offset[i + 1]; ++k) {
      const int j = pairs_.partner[k];
      const double dx = y[3 * i] - y[3 * j], dy = y[3 * i + 1] - y[3 * j + 1],
                   dz = y[3 * i + 2] - y[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= reach_ * reach_) continue;
      const double X0 = p.X[3 * i] - p.X[3 * j], X1 = p.X[3 * i + 1] - p.X[3 * j + 1],
                   X2 = p.X[3 * i + 2] - p.X[3 * j + 2];
      const double d_ij = std::min(0.9 * std::sqrt(X0 * X0 + X1 * X1 + X2 * X2), 1.35 * lc);
      const double r = std::sqrt(r2);
      if (r >= d_ij) continue;
      const double c = m.laws[m.law_of[p.material[i] * materials + p.material[j]]].c;
      // pair_peri_pmb.cpp: rk = 15 c V_j (r - d_ij) / delta, f_i += (x_i - x_j) (-rk / r).
      const double rk = 15.0 * c * p.volume[j] * (d_ij - r) / delta;
      const double scale = r > 0.0 ? rk / r : 0.0;
      fx += scale * dx;
      fy += scale * dy;
      fz += scale * dz;
      e += 0.25 * rk * (d_ij - r) * p.volume[i];
    }
    force[3 * i] += fx;
    force[3 * i + 1] += fy;
    force[3 * i + 2] += fz;
    energy += e;
  }
  return energy;
}

} // namespace mf::pd
