#pragma once
// Closed-form plane-elasticity solutions used as references: displacement and stress at a point.
#include "meshfree/core/types.hpp"
#include "meshfree/materials/elastic.hpp"
#include <variant>

namespace mf::verification {

/// Cantilever x in [0, L], y in [-D/2, D/2], end load P (parabolic shear with resultant +P
/// along y on x = L), unit
/// thickness; Timoshenko & Goodier (1970) section 21, in the form of Belytschko, Lu & Gu
/// (1994) eqs. (41)-(42) with the origin at the clamped end.
struct TimoshenkoBeam {
  double P = 1000.0, L = 48.0, D = 12.0;
};

/// Infinite plate with a hole of radius a under remote tension sigma0 along x, centred at the
/// origin (Kirsch 1898; displacements as in Szabo & Babuska 1991, with kappa of plane stress).
struct KirschPlate {
  double a = 1.0, sigma0 = 1.0;
};

/// Linear displacement field u = u0 + G x (the patch test).
struct LinearField {
  Vec2 u0{0.0, 0.0};
  Mat2 G = Mat2::Zero();
};

using ExactSolution = std::variant<TimoshenkoBeam, KirschPlate, LinearField>;

/// Material for the exact solution: already converted to plane stress with
/// materials::plane_stress_equivalent where the model is plane strain.
Vec2 exact_displacement(const ExactSolution& s, const materials::IsotropicElastic& m,
                        const Vec2& x);
/// Exact stress [sxx, syy, sxy].
Vec3 exact_stress(const ExactSolution& s, const materials::IsotropicElastic& m, const Vec2& x);

} // namespace mf::verification
