#pragma once
// The ordinary state-based linear peridynamic solid (LPS, Silling et al. 2007) as material
// constants and pure functions: its moduli in each kinematic setting, its influence functions and
// its critical stretch from a fracture energy. The force loop is pd/state_based.
//
// With the influence function omega(|xi|), the weighted volume m_i = sum_j omega |xi|^2 V_j and
// the extension e = |y_j - y_i| - |xi| of a bond, the dilatation of particle i in d dimensions is
//   theta_i = (d / m_i) sum_j omega |xi| e V_j                              (d = 3: Silling 2007;
// d = 2: the in-plane trace, Le et al. 2014), and the scalar force state
//   t_i<xi> = (d kappa / m_i) theta_i omega |xi| + (a mu / m_i) omega (e - theta_i |xi| / d),
// a = 15 in 3D and 8 in a plane, derived from the energy density
//   W_i = kappa theta_i^2 / 2 + (a mu / (2 m_i)) sum_j omega (e - theta_i |xi| / d)^2 V_j.
// Under a homogeneous small strain the stress sum_j t ξ⊗ξ/|ξ| V_j is then kappa tr(eps) I +
// 2 mu dev(eps) in 3D and (kappa - mu) tr(eps) I + 2 mu eps in a plane, by the isotropic second
// and fourth moments of the family (Silling et al. 2007): kappa is the bulk modulus in
// 3D and the plane's own bulk modulus in 2D, lambda + mu in plane strain and E / (2 (1 - nu)) in
// plane stress. Any Poisson's ratio follows; bond-based PMB is the case nu = 1/4 (1/3 in plane
// stress), where the two coincide.
#include "meshfree/materials/pd_bonds.hpp"
#include <cmath>

namespace mf::materials {

/// The weight a bond of reference length |xi| has in the family's sums:
///  - InverseLength: omega = 1 / |xi| (LAMMPS peri/lps, PairPeriLPS::influence_function);
///  - Constant: omega = 1;
///  - Gaussian: omega = exp(-|xi|^2 / delta^2) (Seleson & Parks 2011).
enum class Influence { InverseLength, Constant, Gaussian };

inline double influence(Influence f, double length, double delta) {
  switch (f) {
  case Influence::InverseLength:
    return 1.0 / length;
  case Influence::Constant:
    return 1.0;
  case Influence::Gaussian:
    return std::exp(-(length * length) / (delta * delta));
  }
  return 0.0;
}

/// The constants of an LPS material in a kinematic setting: kappa, the modulus of the dilatation
/// (bulk modulus in 3D, the plane's bulk modulus in 2D), and the shear modulus mu.
struct LpsLaw {
  double kappa = 0.0;
  double mu = 0.0;
  double yield_stress = 0.0; // > 0: elastic-plastic (EPS), 3D
  bool plastic() const { return yield_stress > 0.0; }
};

/// The yield value psi0 of the elastic-plastic state-based solid (EPS, Mitchell 2011): the
/// deviatoric force state t^d = (15 mu / m) omega (e^d - e^dp) stays within |t^d|^2 / 2 <= psi0,
/// |t|^2 = sum_j t_j^2 V_j, the return to it radial. Under a homogeneous deviatoric strain
/// eps^d of a family with isotropic moments, |t^d|^2 = (15 mu / m)^2 (2 / 15) M2 eps^d : eps^d
/// with M2 = sum_j omega^2 |xi|^2 V_j; von Mises's yield, 2 mu^2 eps^d : eps^d = sigma_Y^2 / 3,
/// then gives psi0 = 2.5 sigma_Y^2 M2 / m^2 (3D). With omega = 1 and the continuous ball
/// (m = M2 = 4 pi delta^5 / 5) it is Mitchell's 25 sigma_Y^2 / (8 pi delta^5).
inline double eps_yield_value(double yield_stress, double M2, double m) {
  return m > 0.0 ? 2.5 * yield_stress * yield_stress * M2 / (m * m) : 0.0;
}

inline int pd_dimensions(PdDimension d) {
  return d == PdDimension::Solid3D ? 3 : 2;
}

/// LpsLaw from the bulk modulus K and the shear modulus mu:
///   3D: kappa = K;  plane strain: kappa = lambda + mu = K + mu / 3;
///   plane stress: kappa = E / (2 (1 - nu)) = 9 K mu / (3 K + 4 mu).
inline LpsLaw lps_law(PdDimension d, double K, double mu) {
  switch (d) {
  case PdDimension::Solid3D:
    return {K, mu};
  case PdDimension::PlaneStrain:
    return {K + mu / 3.0, mu};
  case PdDimension::PlaneStress:
    return {9.0 * K * mu / (3.0 * K + 4.0 * mu), mu};
  }
  return {};
}

/// The factor a of the deviatoric term: 15 in 3D, 8 in a plane.
inline double lps_deviatoric_factor(PdDimension d) {
  return d == PdDimension::Solid3D ? 15.0 : 8.0;
}

/// Critical stretch from the fracture energy G0 for the LPS material (Madenci & Oterkus 2014,
/// their ordinary state-based critical stretch, written with kappa and mu):
///   3D:    s0 = sqrt(G0 / ((3 mu + (3/4)^4 (kappa - 5 mu / 3)) delta)),
///   plane: s0 = sqrt(G0 / ((6 mu / pi + 16 (kappa - 2 mu) / (9 pi^2)) delta)).
/// At nu = 1/4 (1/3 in plane stress) both equal the bond-based pd_critical_stretch.
inline double lps_critical_stretch(PdDimension d, const LpsLaw& law, double G0, double delta) {
  const double k = law.kappa, mu = law.mu;
  const double modulus = d == PdDimension::Solid3D
                             ? 3.0 * mu + std::pow(0.75, 4) * (k - 5.0 * mu / 3.0)
                             : 6.0 * mu / M_PI + 16.0 * (k - 2.0 * mu) / (9.0 * M_PI * M_PI);
  return std::sqrt(G0 / (modulus * delta));
}

/// The micromodulus of the bond-based body with the same modulus kappa: in 3D c = 18 K / (pi
/// delta^4) (Silling & Askari 2005, eq. 17; LAMMPS peri/lps gives its short-range contact kshort
/// = 15 c, PairPeriLPS::compute), in a plane c = 12 kappa / (pi t delta^3) (pd_micromodulus at
/// nu = 1/4 or 1/3, written with kappa). The short-range contact and the impactors' derived
/// stiffness of an LPS body take it.
inline double lps_contact_micromodulus(PdDimension d, const LpsLaw& law, double delta,
                                       double thickness) {
  return d == PdDimension::Solid3D ? pd_micromodulus_from_bulk(law.kappa, delta)
                                   : 12.0 * law.kappa / (M_PI * thickness * std::pow(delta, 3));
}

} // namespace mf::materials
