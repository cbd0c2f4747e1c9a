#pragma once
// Window (weight) functions of the normalised distance z = r/a, compactly supported on z < 1.
// Cubic B-spline and quartic spline: Liu, Jun & Zhang (1995) and Belytschko, Lu & Gu (1994)
// eq. (9); truncated Gaussian: [Faraji 2007] eq. (2-30), shifted so that it vanishes at z = 1.
#include <cmath>

namespace mf::kernels {

enum class WindowType { CubicSpline, QuarticSpline, Gaussian };

struct Window {
  WindowType type = WindowType::CubicSpline;
  /// c in exp(-(z/c)^2) for the Gaussian. [Faraji 2007]'s exp(-r^2/h^2) truncated at 3h is
  /// c = 1/3 with support a = 3h.
  double gaussian_shape = 0.4;

  double value(double z) const {
    if (z >= 1.0) return 0.0;
    switch (type) {
    case WindowType::CubicSpline:
      return z <= 0.5 ? 2.0 / 3.0 - 4.0 * z * z + 4.0 * z * z * z
                      : 4.0 / 3.0 - 4.0 * z + 4.0 * z * z - 4.0 / 3.0 * z * z * z;
    case WindowType::QuarticSpline:
      return 1.0 - 6.0 * z * z + 8.0 * z * z * z - 3.0 * z * z * z * z;
    case WindowType::Gaussian: {
      const double c2 = gaussian_shape * gaussian_shape;
      const double tail = std::exp(-1.0 / c2);
      return (std::exp(-z * z / c2) - tail) / (1.0 - tail);
    }
    }
    return 0.0;
  }

  /// w'(z) / z, finite as z -> 0 for every window here, so gradients need no special case at r = 0.
  double slope_over_z(double z) const {
    if (z >= 1.0) return 0.0;
    switch (type) {
    case WindowType::CubicSpline:
      return z <= 0.5 ? -8.0 + 12.0 * z : (-4.0 + 8.0 * z - 4.0 * z * z) / z;
    case WindowType::QuarticSpline:
      return -12.0 + 24.0 * z - 12.0 * z * z;
    case WindowType::Gaussian: {
      const double c2 = gaussian_shape * gaussian_shape;
      return -2.0 / c2 * std::exp(-z * z / c2) / (1.0 - std::exp(-1.0 / c2));
    }
    }
    return 0.0;
  }
};

} // namespace mf::kernels
