#pragma once
// Isotropic linear elasticity in 2D Voigt form [xx, yy, xy], engineering shear strain.
#include "meshfree/core/types.hpp"

namespace mf::materials {

enum class PlaneModel { PlaneStress, PlaneStrain };

struct IsotropicElastic {
  double E = 0.0;  // Young's modulus
  double nu = 0.0; // Poisson's ratio
};

/// Plane stress: [Faraji 2007] eq. (3-6), C = E/(1-nu^2) [1 nu 0; nu 1 0; 0 0 (1-nu)/2].
/// Plane strain: C = E/((1+nu)(1-2nu)) [1-nu nu 0; nu 1-nu 0; 0 0 (1-2nu)/2].
inline Mat3 elastic_matrix(const IsotropicElastic& m, PlaneModel model) {
  Mat3 C = Mat3::Zero();
  if (model == PlaneModel::PlaneStress) {
    const double c = m.E / (1.0 - m.nu * m.nu);
    C << c, c * m.nu, 0.0, c * m.nu, c, 0.0, 0.0, 0.0, c * 0.5 * (1.0 - m.nu);
  } else {
    const double c = m.E / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu));
    C << c * (1.0 - m.nu), c * m.nu, 0.0, c * m.nu, c * (1.0 - m.nu), 0.0, 0.0, 0.0,
        c * 0.5 * (1.0 - 2.0 * m.nu);
  }
  return C;
}

/// Out-of-plane stress: zero in plane stress, nu (sxx + syy) in plane strain.
inline double out_of_plane_stress(const IsotropicElastic& m, PlaneModel model, const Vec3& sigma) {
  return model == PlaneModel::PlaneStrain ? m.nu * (sigma(0) + sigma(1)) : 0.0;
}

/// Von Mises equivalent stress from in-plane components and szz.
inline double von_mises(const Vec3& s, double szz) {
  const double sxx = s(0), syy = s(1), sxy = s(2);
  return std::sqrt(
      0.5 * ((sxx - syy) * (sxx - syy) + (syy - szz) * (syy - szz) + (szz - sxx) * (szz - sxx)) +
      3.0 * sxy * sxy);
}

/// Material constants that turn plane-strain elasticity into the plane-stress form used by
/// closed-form solutions: E' = E / (1 - nu^2), nu' = nu / (1 - nu).
inline IsotropicElastic plane_stress_equivalent(const IsotropicElastic& m, PlaneModel model) {
  if (model == PlaneModel::PlaneStress) return m;
  return {m.E / (1.0 - m.nu * m.nu), m.nu / (1.0 - m.nu)};
}

} // namespace mf::materials
