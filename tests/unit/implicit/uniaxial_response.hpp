#pragma once
// The closed-form uniaxial response the elastoplastic tests compare a homogeneous bar with.
#include "meshfree/materials/j2_plasticity.hpp"
#include <cmath>

namespace mf {

/// One-dimensional J2 response (uniaxial stress) with isotropic hardening sigma_y(alpha) and
/// linear kinematic hardening Hk: backward Euler on |sigma - b| - sigma_y(alpha) <= 0, written
/// independently of the 3D return mapping under test.
struct Uniaxial {
  materials::J2Parameters p;
  double plastic = 0.0, back = 0.0, alpha = 0.0;

  double stress(double strain) {
    const double trial = p.E * (strain - plastic);
    const double xi = trial - back;
    if (std::abs(xi) <= materials::yield_stress(p, alpha)) return trial;
    const double sign = xi > 0.0 ? 1.0 : -1.0;
    double dl = 0.0;
    for (int it = 0; it < 100; ++it) {
      const double g =
          std::abs(xi) - (p.E + p.H_kinematic) * dl - materials::yield_stress(p, alpha + dl);
      const double dg = -(p.E + p.H_kinematic) - materials::yield_slope(p, alpha + dl);
      dl -= g / dg;
      if (std::abs(g) < 1e-12 * p.sigma0) break;
    }
    plastic += sign * dl;
    back += sign * p.H_kinematic * dl;
    alpha += dl;
    return trial - sign * p.E * dl;
  }
};

} // namespace mf
