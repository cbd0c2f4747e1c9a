#include "meshfree/pd/model.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::pd {

bool Model::any_plastic() const {
  return std::any_of(laws.begin(), laws.end(), [](const auto& l) { return l.plastic(); });
}

bool Model::any_alpha() const {
  return std::any_of(laws.begin(), laws.end(), [](const auto& l) { return l.alpha != 0.0; });
}

namespace {

/// Whether the segments p0-p1 and q0-q1 of a plane cross (touching counts).
bool segments_cross(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                    const Eigen::Vector3d& q1) {
  const auto cross = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  const Eigen::Vector3d r = p1 - p0, s = q1 - q0;
  const double denom = cross(r, s);
  if (std::abs(denom) < 1e-300) return false; // parallel: a bond along a crack is not cut
  const double t = cross(q0 - p0, s) / denom, u = cross(q0 - p0, r) / denom;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

/// Whether the segment p0-p1 crosses the parallelogram a + s (b - a) + t (c - a).
bool segment_crosses_patch(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                           const PreCrack& c) {
  const Eigen::Vector3d e1 = c.b - c.a, e2 = c.c - c.a, nrm = e1.cross(e2);
  const double d0 = nrm.dot(p0 - c.a), d1 = nrm.dot(p1 - c.a);
  if (d0 * d1 > 0.0 || d0 == d1) return false;
  const Eigen::Vector3d hit = p0 + (d0 / (d0 - d1)) * (p1 - p0);
  // Coordinates of the hit in the (e1, e2) basis.
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
  const Eigen::Vector3d h = hit - c.a;
  const double det = g11 * g22 - g12 * g12;
  const double s = (g22 * h.dot(e1) - g12 * h.dot(e2)) / det;
  const double t = (g11 * h.dot(e2) - g12 * h.dot(e1)) / det;
  return s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0;
}

} // namespace

bool Model::state_plastic() const {
  return std::any_of(lps.begin(), lps.end(), [](const auto& l) { return l.plastic(); });
}

BondState initial_state(const Model& m, const std::vector<PreCrack>& cracks) {
  BondState s;
  const Bonds& b = m.bonds;
  s.intact.assign(b.stored(), 1);
  if (m.any_plastic()) s.plastic.assign(b.stored(), 0.0);
  // EPS: each stored bond's plastic deviatoric extension at both ends.
  if (m.state_plastic()) s.plastic.assign(2 * static_cast<std::size_t>(b.stored()), 0.0);
  const int n = m.particles.size();
  if (m.any_alpha()) {
    double s00 = 0.0;
    for (const auto& l : m.laws) s00 = std::max(s00, l.critical_stretch);
    s.s0.assign(n, s00);
  }
  if (!cracks.empty()) {
    const particles::ParticleSet& p = m.particles;
    const int owned = m.particles.owned_count();
#pragma omp parallel for schedule(dynamic, 256)
    for (int i = 0; i < owned; ++i)
      for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
        const Eigen::Vector3d xi = p.reference(i), xj = p.reference(b.partner[k]);
        for (const PreCrack& c : cracks) {
          const bool cut =
              m.plane() ? segments_cross(xi, xj, c.a, c.b) : segment_crosses_patch(xi, xj, c);
          if (cut) {
            s.intact[k] = 0;
            break;
          }
        }
      }
  }
  return s;
}

void damage(const Model& m, const BondState& s, std::vector<double>& phi) {
  const int n = m.particles.size();
  std::vector<double> kept(n, 0.0);
  for_each_directed_bond(m, [&](int i, int, long k, double w, const BondClass&) {
    if (s.intact[k]) kept[i] += w;
  });
  phi.assign(n, 0.0);
  for (int i = 0; i < m.particles.owned_count(); ++i)
    phi[i] = m.weight_sum[i] > 0.0 ? 1.0 - kept[i] / m.weight_sum[i] : 0.0;
}

double stable_time_step(const Model& m, int* limiting) {
  const int n = m.particles.size();
  // sum_j c w_ij / |xi_ij| per particle, c w_ij folded in the class.
  std::vector<double> sum(n, 0.0);
  for_each_directed_bond(m, [&](int i, int, long, double w, const BondClass& c) {
    sum[i] += m.laws[c.law].c * w / c.length;
  });
  double best = std::numeric_limits<double>::infinity();
  int where = -1;
  for (int i = 0; i < m.particles.owned_count(); ++i) {
    if (sum[i] <= 0.0) continue;
    const double dt = std::sqrt(2.0 * m.particles.density[i] / sum[i]);
    if (dt < best) best = dt, where = i;
  }
  if (limiting) *limiting = where;
  return best;
}

} // namespace mf::pd
