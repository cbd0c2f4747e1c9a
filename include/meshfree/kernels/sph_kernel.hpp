#pragma once
// Smoothing kernels of SPH with support 2h in 1, 2 or 3 dimensions. The cubic B-spline
// (Monaghan & Lattanzio 1985; [Altafi 2018] eq. 3-9):
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

/// c / h^(k+1) for 1 / h given.
inline double over_power(double c, double inv_h, int k) {
  double x = c * inv_h;
  for (int e = 0; e < k; ++e) x *= inv_h;
  return x;
}

/// dW/dr / r for r > 0, the factor of x_ij in grad_i W_ij, evaluated for every interacting pair:
/// 1 / h and 1 / r come from the one division 1 / (h r). Both pieces are evaluated and one
/// selected, so that a loop over pairs compiles to packed code without branches. Inner piece:
/// a_d / h^2 (-3 + 9/4 q); outer: -3/4 a_d / h (2 - q)^2 / r.
inline double cubic_spline_slope_over_r(int dim, double r, double h) {
  const double c = dim == 1 ? 2.0 / 3.0 : dim == 2 ? 10.0 / (7.0 * M_PI) : 1.0 / M_PI; // a_d h^d
  const double inv = 1.0 / (h * r), inv_h = r * inv, inv_r = h * inv, q = r * inv_h;
  const double a = over_power(c, inv_h, dim); // a_d / h
  const double inner = a * inv_h * (-3.0 + 2.25 * q),
               outer = -a * 0.75 * (2.0 - q) * (2.0 - q) * inv_r;
  return q < 1.0 ? inner : q < 2.0 ? outer : 0.0;
}

/// dW/dr.
inline double cubic_spline_slope(int dim, double r, double h) {
  return r > 0.0 ? r * cubic_spline_slope_over_r(dim, r, h) : 0.0;
}

/// The Wendland C2 kernel (Wendland 1995; Dehnen & Aly 2012), support 2h, s = q / 2:
///   1D: W = 5/(8h) (1 - s)^3 (1 + 3s);  2D: 7/(4 pi h^2) (1 - s)^4 (1 + 4s);
///   3D: 21/(16 pi h^3) (1 - s)^4 (1 + 4s).
/// Its Fourier transform is positive, so it does not suffer the pairing instability of the cubic
/// spline at many neighbours.
inline double wendland_c2(int dim, double r, double h) {
  const double q = r / h;
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  if (dim == 1) return 5.0 / (8.0 * h) * t * t * t * (1.5 * q + 1.0);
  const double a = dim == 2 ? 7.0 / (4.0 * M_PI * h * h) : 21.0 / (16.0 * M_PI * h * h * h);
  return a * t * t * t * t * (2.0 * q + 1.0);
}

/// dW/dr / r of the Wendland C2 kernel, for every interacting pair: -15/8 / h^3 (1 - s)^2 in 1D,
/// -5 a_d / h^2 (1 - s)^3 in 2D and 3D (q / r = 1 / h, so no division by r).
inline double wendland_c2_slope_over_r(int dim, double r, double h) {
  const double inv_h = 1.0 / h, q = r * inv_h;
  if (q >= 2.0) return 0.0;
  const double t = 1.0 - 0.5 * q;
  if (dim == 1) return -3.0 * over_power(5.0 / 8.0, inv_h, 2) * t * t;
  const double c = dim == 2 ? 7.0 / (4.0 * M_PI) : 21.0 / (16.0 * M_PI); // a_d h^d
  return -5.0 * over_power(c, inv_h, dim + 1) * t * t * t;
}

/// dW/dr of the Wendland C2 kernel.
inline double wendland_c2_slope(int dim, double r, double h) {
  return r * wendland_c2_slope_over_r(dim, r, h);
}

enum class SphKernel { CubicSpline, WendlandC2 };

inline double sph_kernel(SphKernel k, int dim, double r, double h) {
  return k == SphKernel::CubicSpline ? cubic_spline(dim, r, h) : wendland_c2(dim, r, h);
}
/// W(q h, h) without its normalisation a_d / h^dim, for q = r / h: a ratio of two kernel values
/// at one h (the artificial stress's W(r) / W(dp)) is a ratio of these, with one division for q.
inline double sph_kernel_profile(SphKernel k, int dim, double q) {
  if (!(q < 2.0)) return 0.0;
  if (k == SphKernel::CubicSpline)
    return q < 1.0 ? 1.0 - 1.5 * q * q + 0.75 * q * q * q
                   : 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
  const double t = 1.0 - 0.5 * q;
  return dim == 1 ? t * t * t * (1.5 * q + 1.0) : t * t * t * t * (2.0 * q + 1.0);
}
inline double sph_kernel_slope_over_r(SphKernel k, int dim, double r, double h) {
  return k == SphKernel::CubicSpline ? cubic_spline_slope_over_r(dim, r, h)
                                     : wendland_c2_slope_over_r(dim, r, h);
}

} // namespace mf::kernels
