#pragma once
// Exact solutions of 3D linear elasticity for verification, Voigt order [xx, yy, zz, yz, xz, xy].
#include "meshfree/core/types.hpp"
#include "meshfree/materials/elastic.hpp"
#include <variant>

namespace mf::verification {

/// Linear displacement field u = u0 + G x (the 3D patch test); no body force.
struct LinearField3D {
  Vec3 u0{0.0, 0.0, 0.0};
  Mat3 G = Mat3::Zero();
};

/// A thick-walled cylinder along z about the origin, inner radius a, outer radius b, internal
/// pressure p, in plane strain (u_z = 0) ([Lame 1852]; [Timoshenko & Goodier 1970] ch. 4, stress
/// distributions symmetrical about an axis):
///   sigma_rr = A - B / r^2,  sigma_tt = A + B / r^2,  sigma_zz = 2 nu A,
///   A = p a^2 / (b^2 - a^2),  B = p a^2 b^2 / (b^2 - a^2),
///   u_r = (1 + nu) / E ((1 - 2 nu) A r + B / r).
struct ThickCylinder {
  double a = 1.0, b = 2.0, p = 1.0;
};

/// A hollow sphere about the origin, inner radius a, outer radius b (infinite: a cavity in an
/// unbounded body), internal pressure p ([Lame 1852]; [Timoshenko & Goodier 1970] sec. 137,
/// a hollow sphere submitted to uniform internal pressure):
///   sigma_rr = A (1 - b^3 / r^3),  sigma_tt = sigma_pp = A (1 + b^3 / (2 r^3)),
///   A = p a^3 / (b^3 - a^3),
///   u_r = A / E ((1 - 2 nu) r + (1 + nu) b^3 / (2 r^2)),
/// and for b -> infinity: sigma_rr = -p a^3 / r^3, sigma_tt = p a^3 / (2 r^3),
/// u_r = p a^3 / (4 G r^2).
struct ThickSphere {
  double a = 1.0, b = 2.0, p = 1.0;
};

using ExactSolution3D = std::variant<LinearField3D, ThickCylinder, ThickSphere>;

Vec3 exact_displacement_3d(const ExactSolution3D& s, const materials::IsotropicElastic& m,
                           const Vec3& x);
/// Exact stress, Voigt [xx, yy, zz, yz, xz, xy].
Eigen::Matrix<double, 6, 1> exact_stress_3d(const ExactSolution3D& s,
                                            const materials::IsotropicElastic& m, const Vec3& x);

} // namespace mf::verification
