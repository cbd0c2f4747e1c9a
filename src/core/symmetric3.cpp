#include "meshfree/core/symmetric3.hpp"
#include <algorithm>
#include <cmath>

namespace mf {

namespace {
/// The largest |a_k|: a is scaled by it first, since p^3 below underflows for entries of 1e-103
/// (an SPH particle's first stress under a blast has such) and overflows for 1e103.
double largest_entry(const double a[6]) {
  double m = 0.0;
  for (int k = 0; k < 6; ++k) m = std::max(m, std::abs(a[k]));
  return m;
}

/// The eigenvalues of a whose largest entry is about 1.
std::array<double, 3> unit_eigenvalues(const double a[6]) {
  // [Smith 1961]: with q = tr(a) / 3 and B = (a - q I) / p, p^2 = |a - q I|^2 / 6, the
  // eigenvalues are q + 2 p cos(phi + 2 pi k / 3), cos(3 phi) = det(B) / 2.
  const double off = a[3] * a[3] + a[4] * a[4] + a[5] * a[5];
  const double q = (a[0] + a[1] + a[2]) / 3.0;
  const double d0 = a[0] - q, d1 = a[1] - q, d2 = a[2] - q;
  const double p2 = (d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * off) / 6.0;
  if (!(p2 > 0.0)) return {q, q, q}; // a multiple of the identity
  const double p = std::sqrt(p2);
  const double det = d0 * (d1 * d2 - a[3] * a[3]) - a[5] * (a[5] * d2 - a[3] * a[4]) +
                     a[4] * (a[5] * a[3] - d1 * a[4]);
  const double r = std::clamp(det / (2.0 * p2 * p), -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  const double l1 = q + 2.0 * p * std::cos(phi);
  const double l3 = q + 2.0 * p * std::cos(phi + 2.0 * M_PI / 3.0);
  return {l1, 3.0 * q - l1 - l3, l3};
}
} // namespace

std::array<double, 3> symmetric_eigenvalues(const double a[6]) {
  const double m = largest_entry(a);
  if (!(m > 0.0)) return {a[0], a[0], a[0]}; // zero, or not finite
  const double unit[6] = {a[0] / m, a[1] / m, a[2] / m, a[3] / m, a[4] / m, a[5] / m};
  const std::array<double, 3> l = unit_eigenvalues(unit);
  return {m * l[0], m * l[1], m * l[2]};
}

namespace {
/// A unit eigenvector of a for its simple eigenvalue lambda: the largest of the cross products
/// of two rows of a - lambda I, which span the plane normal to it.
void eigenvector(const double a[6], double lambda, double v[3]) {
  const double r[3][3] = {
      {a[0] - lambda, a[5], a[4]}, {a[5], a[1] - lambda, a[3]}, {a[4], a[3], a[2] - lambda}};
  double best = -1.0;
  for (int i = 0; i < 3; ++i) {
    const double* x = r[i];
    const double* y = r[(i + 1) % 3];
    const double c[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                         x[0] * y[1] - x[1] * y[0]};
    const double n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    if (n > best) best = n, v[0] = c[0], v[1] = c[1], v[2] = c[2];
  }
  const double scale = best > 0.0 ? 1.0 / std::sqrt(best) : 0.0;
  for (int k = 0; k < 3; ++k) v[k] *= scale;
}

/// v^T a v: the eigenvalue of eigenvector v to second order in v's error, where the trigonometric
/// form loses half the digits of the two eigenvalues of a close pair (1e-6 and 0 came out 6e-12
/// off, and with them the positive part).
double rayleigh_quotient(const double a[6], const double v[3]) {
  return a[0] * v[0] * v[0] + a[1] * v[1] * v[1] + a[2] * v[2] * v[2] +
         2.0 * (a[3] * v[1] * v[2] + a[4] * v[0] * v[2] + a[5] * v[0] * v[1]);
}

/// out = a + s v v^T.
void add_dyad(const double a[6], double s, const double v[3], double out[6]) {
  out[0] = a[0] + s * v[0] * v[0], out[1] = a[1] + s * v[1] * v[1], out[2] = a[2] + s * v[2] * v[2];
  out[3] = a[3] + s * v[1] * v[2], out[4] = a[4] + s * v[0] * v[2], out[5] = a[5] + s * v[0] * v[1];
}
} // namespace

void positive_part(const double a[6], double out[6]) {
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  const double m = largest_entry(a);
  if (!(m > 0.0)) { // zero (or not finite, which the caller's checks report)
    std::copy(zero, zero + 6, out);
    return;
  }
  const double unit[6] = {a[0] / m, a[1] / m, a[2] / m, a[3] / m, a[4] / m, a[5] / m};
  const std::array<double, 3> l = unit_eigenvalues(unit);
  double v[3];
  if (l[0] <= 0.0) { // no tension
    std::copy(zero, zero + 6, out);
  } else if (l[2] >= 0.0) { // no compression
    std::copy(a, a + 6, out);
  } else if (l[1] <= 0.0) { // one tensile eigenvalue, apart from the others by at least itself
    eigenvector(unit, l[0], v);
    add_dyad(zero, m * rayleigh_quotient(unit, v), v, out);
  } else { // one compressive eigenvalue, taken away
    eigenvector(unit, l[2], v);
    add_dyad(a, -m * rayleigh_quotient(unit, v), v, out);
  }
}

} // namespace mf
