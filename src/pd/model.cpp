#include "meshfree/pd/model.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/neighbors/pair_list.hpp"
#include "meshfree/pd/forces.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace mf::pd {

bool Model::any_plastic() const {
  return std::any_of(laws.begin(), laws.end(), [](const auto& l) { return l.plastic(); });
}

bool Model::any_alpha() const {
  return std::any_of(laws.begin(), laws.end(), [](const auto& l) { return l.alpha != 0.0; });
}

namespace {

/// Fraction of the cube (square in a plane) of side dx centred at offset xi that lies inside the
/// ball of radius delta, from a uniform sub-grid of the cell.
double cell_fraction_inside(const Eigen::Vector3d& xi, double dx, double delta, bool plane) {
  const int k = plane ? 16 : 8;
  const double h = dx / k, d2 = delta * delta;
  int inside = 0, total = 0;
  for (int c = 0; c < (plane ? 1 : k); ++c)
    for (int b = 0; b < k; ++b)
      for (int a = 0; a < k; ++a) {
        const double x = xi.x() + (a + 0.5) * h - 0.5 * dx;
        const double y = xi.y() + (b + 0.5) * h - 0.5 * dx;
        const double z = plane ? 0.0 : xi.z() + (c + 0.5) * h - 0.5 * dx;
        inside += x * x + y * y + z * z <= d2 ? 1 : 0;
        ++total;
      }
  return static_cast<double>(inside) / total;
}

} // namespace

void build_bonds(Model& m, const LawTable& table, VolumeCorrection correction) {
  MF_REQUIRE(m.horizon > 0.0 && m.spacing > 0.0, "peridynamics: horizon and spacing must be set");
  MF_REQUIRE(!table.laws.empty() && table.laws.size() < 256, "peridynamics: 1 to 255 bond laws");
  const particles::ParticleSet& p = m.particles;
  const double r = 0.5 * m.spacing;
  const bool plane = m.plane();
  // Exact partial volumes reach neighbours whose cells only touch the horizon.
  const double reach = correction == VolumeCorrection::Exact
                           ? m.horizon + r * std::sqrt(plane ? 2.0 : 3.0)
                           : m.horizon;
  const neighbors::PairList pairs = neighbors::pairs_within(p.X, reach);
  Bonds& b = m.bonds;
  const int n = p.size();
  std::vector<long> offset(n + 1, 0);
  std::vector<int> partner;
  std::vector<double> length, weight;
  partner.reserve(pairs.partner.size());
  length.reserve(pairs.partner.size());
  weight.reserve(pairs.partner.size());
  const double inner = m.horizon - r * std::sqrt(plane ? 2.0 : 3.0);
  // On a lattice the fraction depends only on the offset in spacings: computed once per offset.
  std::unordered_map<long long, double> fraction_of_offset;
  const auto fraction = [&](const Eigen::Vector3d& d) {
    const Eigen::Vector3d cells = d / m.spacing;
    const Eigen::Vector3d rounded = cells.array().round();
    if ((cells - rounded).cwiseAbs().maxCoeff() > 1e-6)
      return cell_fraction_inside(d, m.spacing, m.horizon, plane);
    const long long key = ((static_cast<long long>(rounded.x()) + 1000) * 2001 +
                           (static_cast<long long>(rounded.y()) + 1000)) *
                              2001 +
                          (static_cast<long long>(rounded.z()) + 1000);
    auto it = fraction_of_offset.find(key);
    if (it != fraction_of_offset.end()) return it->second;
    const double f = cell_fraction_inside(d, m.spacing, m.horizon, plane);
    fraction_of_offset.emplace(key, f);
    return f;
  };
  const int owned = p.owned_count();
  std::vector<int> row;
  for (int i = 0; i < n; ++i) {
    // Partners in increasing global id: a particle's force sums its bonds in the same order
    // whichever rank holds it and wherever its partners are.
    row.assign(pairs.partner.begin() + pairs.offset[i],
               pairs.partner.begin() + pairs.offset[i + 1]);
    std::sort(row.begin(), row.end(), [&p](int a, int b) { return p.id[a] < p.id[b]; });
    for (std::size_t q = 0; q < row.size() && i < owned; ++q) {
      const int j = row[q];
      const Eigen::Vector3d d = p.reference(j) - p.reference(i);
      const double xi = d.norm();
      double beta = 1.0;
      if (correction == VolumeCorrection::Linear && xi > m.horizon - r)
        beta = (m.horizon + r - xi) / (2.0 * r);
      else if (correction == VolumeCorrection::Exact && xi > inner)
        beta = fraction(d);
      if (beta <= 0.0) continue;
      partner.push_back(j);
      length.push_back(xi);
      weight.push_back(p.volume[j] * beta);
    }
    offset[i + 1] = static_cast<long>(partner.size());
  }
  b.offset = std::move(offset);
  b.partner = std::move(partner);
  b.length = std::move(length);
  b.weight = std::move(weight);
  b.law.resize(b.count());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k)
      b.law[k] = static_cast<unsigned char>(
          table.law_of[p.material[i] * table.materials + p.material[b.partner[k]]]);
  m.laws = table.laws;
  m.law_of = table.law_of;
  m.weight_sum.assign(n, 0.0);
  for (int i = 0; i < n; ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) m.weight_sum[i] += b.weight[k];
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

BondState initial_state(const Model& m, const std::vector<PreCrack>& cracks) {
  BondState s;
  const Bonds& b = m.bonds;
  s.intact.assign(b.count(), 1);
  if (m.any_plastic()) s.plastic.assign(b.count(), 0.0);
  const int n = m.particles.size();
  if (m.any_alpha()) {
    double s00 = 0.0;
    for (const auto& l : m.laws) s00 = std::max(s00, l.critical_stretch);
    s.s0.assign(n, s00);
  }
  if (!cracks.empty()) {
    const particles::ParticleSet& p = m.particles;
#pragma omp parallel for schedule(dynamic, 256)
    for (int i = 0; i < n; ++i)
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

void apply_surface_correction(Model& m) {
  const particles::ParticleSet& p = m.particles;
  const int n = p.size();
  const int dims = m.plane() ? 2 : 3;
  const int materials = static_cast<int>(m.material_names.size());
  // Strain energy density of a uniaxial strain eps along an axis in the continuum limit of a
  // full horizon, from the bond law itself (small strain, s = eps cos^2):
  //   3D:  W = pi c delta^4 eps^2 / 20,   2D:  W = pi c t delta^3 eps^2 / 16,
  // which is (lambda + 2 mu) eps^2 / 2 with the calibration of c (E / (1 - nu^2) in plane stress).
  const double eps = 1e-3;
  const auto classical = [&](int material) {
    const double c = m.laws[m.law_of[material * materials + material]].c;
    return m.plane() ? M_PI * c * m.thickness * std::pow(m.horizon, 3) * eps * eps / 16.0
                     : M_PI * c * std::pow(m.horizon, 4) * eps * eps / 20.0;
  };
  Model elastic = m; // the factors are those of the elastic bonds
  for (auto& law : elastic.laws)
    law.critical_stretch = 0.0, law.yield_stretch = 0.0, law.alpha = 0.0;
  BondState intact;
  intact.intact.assign(m.bonds.count(), 1);
  std::vector<std::vector<double>> factor(dims, std::vector<double>(n, 1.0));
  for (int d = 0; d < dims; ++d) {
    std::vector<double> y = p.X, f, w;
    for (int i = 0; i < n; ++i) y[3 * i + d] *= 1.0 + eps;
    bond_forces(elastic, intact, y, f, true, &w);
    for (int i = 0; i < n; ++i)
      if (w[i] > 0.0) factor[d][i] = classical(p.material[i]) / w[i];
    m.halo.exchange(factor[d]); // a bond to a ghost takes its owner's factor
  }
  // Each bond takes the mean factor of its ends along each axis, combined by its direction
  // (Madenci & Oterkus 2014, eq. 4.12).
  Bonds& b = m.bonds;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const int j = b.partner[k];
      const Eigen::Vector3d e = (p.reference(j) - p.reference(i)) / b.length[k];
      double sum = 0.0;
      for (int d = 0; d < dims; ++d) {
        const double g = 0.5 * (factor[d][i] + factor[d][j]);
        sum += e(d) * e(d) / (g * g);
      }
      b.weight[k] /= std::sqrt(sum);
    }
  for (int i = 0; i < n; ++i) {
    m.weight_sum[i] = 0.0;
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) m.weight_sum[i] += b.weight[k];
  }
}

void damage(const Model& m, const BondState& s, std::vector<double>& phi) {
  const int n = m.particles.size();
  phi.assign(n, 0.0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    double kept = 0.0;
    for (long k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k)
      if (s.intact[k]) kept += m.bonds.weight[k];
    phi[i] = m.weight_sum[i] > 0.0 ? 1.0 - kept / m.weight_sum[i] : 0.0;
  }
}

double stable_time_step(const Model& m, int* limiting) {
  const int n = m.particles.size();
  double best = std::numeric_limits<double>::infinity();
  int where = -1;
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (long k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k)
      sum += m.laws[m.bonds.law[k]].c * m.bonds.weight[k] / m.bonds.length[k];
    if (sum <= 0.0) continue;
    const double dt = std::sqrt(2.0 * m.particles.density[i] / sum);
    if (dt < best) best = dt, where = i;
  }
  if (limiting) *limiting = where;
  return best;
}

} // namespace mf::pd
