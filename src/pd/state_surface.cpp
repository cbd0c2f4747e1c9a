// The position-aware influence of an LPS body (pd/state_surface.hpp): each particle's Gram
// matrices of the bond directions' quadratic and quartic forms over its family, solved for the
// coefficients; the bonds re-classed with the factors of both their ends.
#include "meshfree/pd/state_surface.hpp"
#include "class_table.hpp"
#include "meshfree/core/error.hpp"
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace mf::pd {

namespace {

/// The forms of a unit direction n: `q` the components of n n in an orthonormal basis of
/// symmetric tensors, `g` the products p_a p_b (a <= b) of p_a = n . D_a . n over an orthonormal
/// basis D_a of deviatoric tensors: 3 and 3 in a plane, 6 and 15 in 3D.
struct Forms {
  int dil = 0, dev = 0;
  double q[6], g[15];
};

Forms forms_of(const Eigen::Vector3d& n, bool plane) {
  const double r2 = std::sqrt(2.0), xx = n.x() * n.x(), yy = n.y() * n.y(), zz = n.z() * n.z();
  Forms f;
  double p[5];
  int np = 0;
  if (plane) {
    f.dil = 3;
    const double q[3] = {xx, yy, r2 * n.x() * n.y()};
    std::copy(q, q + 3, f.q);
    p[0] = (xx - yy) / r2, p[1] = r2 * n.x() * n.y(), np = 2;
  } else {
    f.dil = 6;
    const double q[6] = {xx, yy, zz, r2 * n.x() * n.y(), r2 * n.y() * n.z(), r2 * n.x() * n.z()};
    std::copy(q, q + 6, f.q);
    p[0] = (xx - yy) / r2, p[1] = (xx + yy - 2.0 * zz) / std::sqrt(6.0);
    p[2] = q[3], p[3] = q[4], p[4] = q[5], np = 5;
  }
  for (int a = 0; a < np; ++a)
    for (int b = a; b < np; ++b) f.g[f.dev++] = p[a] * p[b];
  return f;
}

/// The right-hand sides: the identity in the q basis (the dilatation's second moment), 2 delta_ab
/// in the g basis (the deviatoric energy of a unit shear modulus).
Eigen::VectorXd dilatation_target(bool plane) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(plane ? 3 : 6);
  r.head(plane ? 2 : 3).setOnes();
  return r;
}

Eigen::VectorXd deviatoric_target(bool plane) {
  const int np = plane ? 2 : 5;
  Eigen::VectorXd r(np * (np + 1) / 2);
  int k = 0;
  for (int a = 0; a < np; ++a)
    for (int b = a; b < np; ++b) r(k++) = a == b ? 2.0 : 0.0;
  return r;
}

/// The unit direction of a bond from i to j in the reference configuration.
Eigen::Vector3d direction(const particles::ParticleSet& p, int i, int j) {
  return (p.reference(j) - p.reference(i)).normalized();
}

/// Solves G x = r for a particle's coefficients into `out`; false where G is not safely
/// positive definite (too few or collinear bonds).
bool solve_gram(const Eigen::MatrixXd& G, const Eigen::VectorXd& r, double* out) {
  const Eigen::LDLT<Eigen::MatrixXd> f(G);
  if (f.info() != Eigen::Success || !f.isPositive() || f.rcond() < 1e-12) return false;
  const Eigen::VectorXd x = f.solve(r);
  std::copy(x.data(), x.data() + x.size(), out);
  return true;
}

/// The coefficients of every owned particle (`per` a particle: Lambda's, then c's; NaN where
/// the family could not fix them), in chunks of 4,096 particles, each a pass over the bonds, so
/// that the Gram matrices of one chunk only are held (2.1 KB a particle in 3D: 8.6 MB). Returns
/// the particles left with the LPS's.
long coefficients(const Model& m, const BondState& s, int per, std::vector<double>& coef) {
  const particles::ParticleSet& p = m.particles;
  const bool plane = m.plane();
  const int owned = p.owned_count(), nd = plane ? 3 : 6, nv = plane ? 3 : 15;
  const Eigen::VectorXd rd = dilatation_target(plane), rv = deviatoric_target(plane);
  std::vector<double> omega(m.bonds.classes.size());
  for (std::size_t c = 0; c < omega.size(); ++c)
    omega[c] = materials::influence(m.influence, m.bonds.classes[c].length, m.horizon);
  coef.assign(static_cast<std::size_t>(per) * p.size(), std::numeric_limits<double>::quiet_NaN());
  constexpr int kChunk = 4096;
  long left = 0;
  for (int lo = 0; lo < owned; lo += kChunk) {
    const int hi = std::min(owned, lo + kChunk);
    std::vector<Eigen::MatrixXd> Gd(hi - lo, Eigen::MatrixXd::Zero(nd, nd));
    std::vector<Eigen::MatrixXd> Gv(hi - lo, Eigen::MatrixXd::Zero(nv, nv));
    for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
      if (i < lo || i >= hi || !s.intact[k]) return;
      const Forms f = forms_of(direction(p, i, j), plane);
      const double a = omega[&c - m.bonds.classes.data()] * c.length * c.length * w;
      const Eigen::Map<const Eigen::VectorXd> q(f.q, nd), g(f.g, nv);
      Gd[i - lo].noalias() += a * q * q.transpose();
      Gv[i - lo].noalias() += a * g * g.transpose();
    });
    for (int i = lo; i < hi; ++i) {
      double* out = &coef[static_cast<std::size_t>(per) * i];
      if (!solve_gram(Gd[i - lo], rd, out) || !solve_gram(Gv[i - lo], rv, out + nd)) {
        std::fill(out, out + per, std::numeric_limits<double>::quiet_NaN());
        ++left;
      }
    }
  }
  return left;
}

/// A factor rounded to a multiple of 2^-36 (1.5e-11): the particles of a lattice whose families
/// are alike differ in their Gram matrices by the round-off of the positions alone, which would
/// give every bond a class of its own (a 36^3 lattice: 469 MiB instead of 78, the force loop 5
/// times slower through the scattered classes).
double rounded(double factor) {
  constexpr double kScale = 68719476736.0; // 2^36
  return std::round(factor * kScale) / kScale;
}

/// A bond end's factors over the LPS's: (q . Lambda_i) m_i / d and (g . c_i) m_i / a; 1 where the
/// particle kept the LPS's influence.
std::pair<double, double> end_factors(const Forms& f, const double* coef, double mi, double d,
                                      double a) {
  if (std::isnan(coef[0])) return {1.0, 1.0};
  double dil = 0.0, dev = 0.0;
  for (int e = 0; e < f.dil; ++e) dil += f.q[e] * coef[e];
  for (int e = 0; e < f.dev; ++e) dev += f.g[e] * coef[f.dil + e];
  return {rounded(dil * mi / d), rounded(dev * mi / a)};
}

} // namespace

long apply_position_aware_influence(Model& m, const BondState& s) {
  MF_REQUIRE(m.state_based() && !m.state_plastic(),
             "position-aware influence: the body is not an elastic LPS body");
  MF_REQUIRE(m.weighted_volume.size() == static_cast<std::size_t>(m.particles.size()),
             "position-aware influence: the weighted volumes are not set");
  const particles::ParticleSet& p = m.particles;
  const bool plane = m.plane();
  const int per = plane ? 6 : 21;
  std::vector<double> coef;
  const long left = coefficients(m, s, per, coef);
  m.halo.exchange(coef, per); // a bond to a ghost takes its owner's coefficients
  const double d = materials::pd_dimensions(m.dimension);
  const double a = materials::lps_deviatoric_factor(m.dimension);
  Bonds& b = m.bonds;
  const std::vector<BondClass> before = std::move(b.classes);
  b.classes.clear();
  detail::ClassTable classes(b.classes);
  for (int i = 0; i < p.owned_count(); ++i)
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const int j = b.partner[k];
      const Forms f = forms_of(direction(p, i, j), plane);
      BondClass like = before[b.cls[k]];
      std::tie(like.dil, like.dev) =
          end_factors(f, &coef[per * static_cast<std::size_t>(i)], m.weighted_volume[i], d, a);
      std::tie(like.dil_partner, like.dev_partner) =
          end_factors(f, &coef[per * static_cast<std::size_t>(j)], m.weighted_volume[j], d, a);
      b.cls.set(k, classes.find(like));
    }
  fold_laws(m);
  m.position_aware = true;
  return static_cast<long>(m.halo.ranks().sum(static_cast<double>(left)));
}

} // namespace mf::pd

namespace mf::pd {

namespace {

/// A bond's factors seen from the end `i` that for_each_directed_bond passes first: the row
/// particle's are dil and dev, the partner's dil_partner and dev_partner.
struct EndFactors {
  double di, dj, vi, vj;
};

EndFactors end_factors_of(const Model& m, long k, int j, const BondClass& c) {
  const bool row = m.bonds.partner[k] == j; // i is the row particle
  return row ? EndFactors{c.dil, c.dil_partner, c.dev, c.dev_partner}
             : EndFactors{c.dil_partner, c.dil, c.dev_partner, c.dev};
}

} // namespace

std::vector<double> position_aware_fictitious_density(const Model& m, const BondState& s) {
  // As state_fictitious_density, a quarter of the absolute row sum of the linearised stiffness,
  // bounded term by term: t_ij = omega |xi| dil_i (d kappa theta_i - Q_i) / m_i + b_i dev_ij e^d,
  // Q_i = b_i sum_k omega |xi| w (dev_k - dil_k S_i / m_i) e_k with S_i = sum omega dev |xi|^2 w,
  // which vanishes where the factors are the LPS's.
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  const Bonds& bonds = m.bonds;
  std::vector<double> omega(bonds.classes.size());
  for (std::size_t c = 0; c < omega.size(); ++c)
    omega[c] = materials::influence(m.influence, bonds.classes[c].length, m.horizon);
  const double d = materials::pd_dimensions(m.dimension);
  const double a = materials::lps_deviatoric_factor(m.dimension);
  const auto om = [&](const BondClass& c) { return omega[&c - bonds.classes.data()]; };
  // Per particle: b_i, S^dil_i = sum omega dil |xi| w, S_i, then R_i = sum omega |xi| w |dev -
  // dil S_i / m_i| (the row sum of Q_i / b_i).
  std::vector<double> b(n, 0.0), Sd(n, 0.0), S(n, 0.0), R(n, 0.0);
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const EndFactors f = end_factors_of(m, k, j, c);
    Sd[i] += om(c) * f.di * c.length * w;
    S[i] += om(c) * f.vi * c.length * c.length * w;
  });
  for (int i = 0; i < n; ++i) {
    const double mi = m.weighted_volume[i];
    b[i] = mi > 0.0 ? a * m.lps[q.material[i]].mu / mi : 0.0;
  }
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k] || m.weighted_volume[i] <= 0.0) return;
    const EndFactors f = end_factors_of(m, k, j, c);
    R[i] += om(c) * c.length * w * std::abs(f.vi - f.di * S[i] / m.weighted_volume[i]);
  });
  m.halo.exchange(Sd), m.halo.exchange(R);
  // The coupling of one end's dilatation and Q to the bond's force, per unit omega |xi| w.
  const auto coupling = [&](int i, double di, double vi) {
    const double mi = m.weighted_volume[i];
    if (mi <= 0.0) return 0.0;
    const double kappa = m.lps[q.material[i]].kappa;
    return std::abs(di * d * kappa / mi - b[i] * vi / d) * d / mi * Sd[i] +
           std::abs(di) * b[i] / mi * R[i];
  };
  const double root3 = std::sqrt(3.0);
  std::vector<double> lambda(3 * static_cast<std::size_t>(n), 0.0);
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const EndFactors f = end_factors_of(m, k, j, c);
    const double L = c.length;
    const double e[3] = {(q.X[3 * j] - q.X[3 * i]) / L, (q.X[3 * j + 1] - q.X[3 * i + 1]) / L,
                         (q.X[3 * j + 2] - q.X[3 * i + 2]) / L};
    const double row = std::abs(e[0]) + std::abs(e[1]) + std::abs(e[2]);
    const double deviatoric = om(c) * (b[i] * std::abs(f.vi) + b[j] * std::abs(f.vj)) * w;
    const double dilatation = om(c) * L * w * (coupling(i, f.di, f.vi) + coupling(j, f.dj, f.vj));
    for (int e_d = 0; e_d < 3; ++e_d)
      lambda[3 * i + e_d] += 0.5 * deviatoric * std::abs(e[e_d]) * row + 0.5 * root3 * dilatation;
  });
  return lambda;
}

} // namespace mf::pd
