#pragma once
// J2 (von Mises) plasticity with isotropic and linear kinematic hardening, backward Euler, as
// pure functions: parameters, total strain and committed history in; stress, algorithmic
// (consistent) tangent and trial history out. Nothing here knows about nodes or particles.
//
//  - 3D: radial return and its consistent tangent (Simo & Hughes 1998, Boxes 3.1-3.2; Simo &
//    Taylor 1985), with a local Newton iteration on the consistency parameter for nonlinear
//    isotropic hardening.
//  - Plane strain: the 3D update with eps_zz = 0.
//  - Plane stress: the projected return (Simo & Taylor 1986; de Souza Neto, Peric & Owen 2008,
//    ch. 9) with linear kinematic hardening: one scalar Newton iteration on the plastic
//    multiplier in the eigenbasis shared by the projection onto the deviator and the
//    plane-stress elasticity, and its consistent tangent. It is the 3D backward-Euler step with
//    sigma_zz = 0 (the tests hold it to the 3D update at its eps_zz), with one scalar iteration
//    where iterating the 3D update on eps_zz nests one inside another.
//
// Voigt order 3D [xx, yy, zz, yz, xz, xy], 2D [xx, yy, xy]; engineering shear strains.
#include "meshfree/materials/stress_update.hpp"
#include <variant>
#include <vector>

namespace mf::materials {

/// Isotropic hardening laws: the uniaxial yield stress as a function of the equivalent plastic
/// strain alpha.
struct PerfectPlastic {};
struct LinearHardening {
  double H = 0.0; // sigma_y = sigma0 + H alpha
};
/// Saturation (Voce) plus linear: sigma_y = sigma0 + H alpha + (sinf - sigma0)(1 - exp(-delta
/// alpha)).
struct VoceHardening {
  double H = 0.0, sigma_inf = 0.0, delta = 0.0;
};
/// Power law (Swift): sigma_y = K (eps0 + alpha)^n; sigma0 is then K eps0^n.
struct SwiftHardening {
  double K = 0.0, eps0 = 0.0, n = 0.0;
};
/// Piecewise-linear table of (alpha, sigma_y), alpha increasing from 0; beyond the last point the
/// last slope continues.
struct TableHardening {
  std::vector<double> alpha, sigma;
};
using IsotropicHardening =
    std::variant<PerfectPlastic, LinearHardening, VoceHardening, SwiftHardening, TableHardening>;

struct J2Parameters {
  double E = 0.0, nu = 0.0;
  double sigma0 = 0.0; // initial yield stress (ignored by Swift and table laws, which define it)
  IsotropicHardening hardening = PerfectPlastic{};
  double H_kinematic = 0.0; // linear (Prager) kinematic modulus: uniaxial slope adds H_kinematic
};

/// Uniaxial yield stress and its slope at alpha.
double yield_stress(const J2Parameters& p, double alpha);
double yield_slope(const J2Parameters& p, double alpha);

StressUpdate3D j2_update_3d(const J2Parameters& p, const Vec6& strain,
                            const MaterialState& committed);
StressUpdate2D j2_update_plane_strain(const J2Parameters& p, const Vec3& strain,
                                      const MaterialState& committed);
StressUpdate2D j2_update_plane_stress(const J2Parameters& p, const Vec3& strain,
                                      const MaterialState& committed);

/// The radial return of J2 plasticity with isotropic and linear kinematic hardening (Simo &
/// Hughes 1998, Box 3.2): a trial deviator s_trial (stress-like Voigt) with back stress beta at
/// equivalent plastic strain alpha. j2_update_3d forms the trial deviator from a total strain;
/// codes that integrate the deviatoric stress rate (explicit SPH) pass the integrated deviator.
/// Backward Euler on the consistency equation
///   |xi_trial| - 2 mu dgamma - (2/3) Hk dgamma - sqrt(2/3) sigma_y(alpha + sqrt(2/3) dgamma) = 0,
/// xi_trial = s_trial - beta; the deviator returns along n = xi_trial / |xi_trial|.
struct J2Return {
  bool plastic = false;
  double dgamma = 0.0;     // plastic multiplier
  double alpha = 0.0;      // equivalent plastic strain after the step
  double trial_norm = 0.0; // |xi_trial|
  Vec6 normal = Vec6::Zero();
  Vec6 deviator = Vec6::Zero();    // s_trial - 2 mu dgamma n
  Vec6 back_stress = Vec6::Zero(); // beta + (2/3) Hk dgamma n
};
J2Return j2_radial_return(const J2Parameters& p, const Vec6& s_trial, const Vec6& back_stress,
                          double alpha);

/// Von Mises stress of a 3D stress vector.
double von_mises_3d(const Vec6& s);

} // namespace mf::materials
