#pragma once
// The cubic B-spline smoothing kernel of SPH (Monaghan & Lattanzio 1985; the thesis' eq. 3-19),
// support 2h, in 1, 2 or 3 dimensions:
//   W(q) = a_d (1 - 3/2 q^2 + 3/4 q^3) for 0 <= q < 1, a_d (2 - q)^3 / 4 for 1 <= q < 2, 0 beyond,
//   q = r / h, a_1 = 2 / (3h), a_2 = 10 / (7 pi h^2), a_3 = 1 / (pi h^3).
#include <cmath>

namespace mf::kernels {

inline double cubic_spline_norm(int dim, double h) {
  return dim == 1   ? 2.0 / (3.0 * h)
         : dim == 2 ? 10.0 / (7.0 * M_PI * h * h)
                    : 1.0 / (M_PI * h * h * h);
}

inline double cubic_spline(int dim, double r, double h) {
  const double q = r / h, a = cubic_spline_norm(dim, h);
  if (q < 1.0) return a * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
  if (q < 2.0) return a * 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
  return 0.0;
}

/// dW/dr.
inline double cubic_spline_slope(int dim, double r, double h) {
  const double q = r / h, a = cubic_spline_norm(dim, h) / h;
  if (q < 1.0) return a * (-3.0 * q + 2.25 * q * q);
  if (q < 2.0) return -a * 0.75 * (2.0 - q) * (2.0 - q);
  return 0.0;
}

} // namespace mf::kernels
