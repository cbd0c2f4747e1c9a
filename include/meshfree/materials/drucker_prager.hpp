#pragma once
// Drucker-Prager plasticity for soils and rock, backward Euler, as pure functions in the form of
// de Souza Neto, Peric & Owen 2008 (section 8.3) and Drucker & Prager 1952: the cone
//   Phi = sqrt(J2(s)) + eta p - xi c(alpha),      p = tr(sigma) / 3 (tension positive),
// a flow potential sqrt(J2) + eta_bar p (eta_bar = eta: associated flow), cohesion hardening
// c = c0 + H alpha with alpha' = xi dgamma, the return to the smooth cone or to its apex, and a
// tension cut-off p <= T below the apex (a plane on the hydrostatic axis, returned to alone or
// together with the cone along their circle of intersection). Each return is closed-form for
// the linear hardening law, and each has its consistent tangent.
//
// The cone's constants from Mohr-Coulomb's c and phi (de Souza Neto et al. 2008, section
// 6.4): the plane-strain match (collapse loads of Mohr-Coulomb under plane strain and
// associated flow) eta = 3 tan(phi) / sqrt(9 + 12 tan^2 phi), xi = 3 / sqrt(9 + 12 tan^2 phi);
// the outer cone (through Mohr-Coulomb's compressive meridians) eta = 6 sin(phi) / (sqrt 3 (3 -
// sin phi)), xi = 6 cos(phi) / (sqrt 3 (3 - sin phi)); the inner cone (tensile meridians) with
// 3 + sin(phi). The dilatancy eta_bar follows from psi by the same match as eta from phi.
#include "meshfree/materials/stress_update.hpp"
#include <limits>

namespace mf::materials {

enum class MohrCoulombMatch { PlaneStrain, Outer, Inner };

struct DruckerPragerParameters {
  double E = 0.0, nu = 0.0;
  double cohesion = 0.0;  // c0
  double hardening = 0.0; // H = dc / dalpha (>= 0)
  double eta = 0.0;       // friction
  double xi = 1.0;        // cohesion factor
  double eta_bar = 0.0;   // dilatancy (the flow potential's eta)
  double tension_cutoff = std::numeric_limits<double>::infinity(); // T: p <= T
};

/// The cone's (eta, xi) for a friction angle phi [rad] (eta of a dilatancy angle alike).
struct ConeConstants {
  double eta = 0.0, xi = 1.0;
};
ConeConstants mohr_coulomb_cone(double phi, MohrCoulombMatch match);

/// The mean stress of the apex at cohesion c: xi c / eta (infinite for eta = 0).
double apex_pressure(const DruckerPragerParameters& p, double cohesion);

/// Phi at a stress (with the cohesion of alpha): > 0 outside the cone.
double drucker_prager_yield(const DruckerPragerParameters& p, const Vec6& stress, double alpha);

/// The backward-Euler update at the total strain `strain` from the committed history: the return
/// to the cone, its apex, the tension cut-off or the cone's circle on the cut-off, whichever
/// holds, and its consistent tangent (unsymmetric when eta_bar != eta).
StressUpdate3D drucker_prager_update_3d(const DruckerPragerParameters& p, const Vec6& strain,
                                        const MaterialState& committed);

} // namespace mf::materials
