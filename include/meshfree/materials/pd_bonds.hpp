#pragma once
// Bond-based peridynamic material constants and bond laws as pure functions: micromodulus and
// critical stretch from the engineering constants, and the force of one bond from its stretch.
// Nothing here knows about particles or bond lists.
//
// Pairwise force density between points x and x' (Silling 2000; Silling & Askari 2005):
//   f = mu(t) c (s - s_p) e,   s = (|y' - y| - |x' - x|) / |x' - x|,   e = (y' - y) / |y' - y|,
// mu the intact flag (breaking is irreversible), s_p the plastic stretch of the micro-plastic
// bond (zero for PMB).
#include <cmath>

namespace mf::materials {

/// The kinematic setting of a bond-based model: a 3D solid, or a 2D plate of thickness t in
/// plane stress or plane strain. Bond-based peridynamics fixes Poisson's ratio: 1/4 in 3D and in
/// plane strain, 1/3 in plane stress.
enum class PdDimension { Solid3D, PlaneStress, PlaneStrain };

inline double pd_poisson_ratio(PdDimension d) {
  return d == PdDimension::PlaneStress ? 1.0 / 3.0 : 0.25;
}

/// Micromodulus c from Young's modulus, horizon delta and (2D) thickness t:
///   3D:            c = 12 E / (pi delta^4)         (Silling & Askari 2005, eq. 17 with k = 2E/3)
///   plane stress:  c = 9 E / (pi t delta^3)        (Madenci & Oterkus 2014, sec. 2.6; paper 000
///   eq. 5) plane strain:  c = 48 E / (5 pi t delta^3)     (paper 000 eq. 5)
inline double pd_micromodulus(PdDimension d, double E, double delta, double thickness) {
  switch (d) {
  case PdDimension::Solid3D:
    return 12.0 * E / (M_PI * std::pow(delta, 4));
  case PdDimension::PlaneStress:
    return 9.0 * E / (M_PI * thickness * std::pow(delta, 3));
  case PdDimension::PlaneStrain:
    return 48.0 * E / (5.0 * M_PI * thickness * std::pow(delta, 3));
  }
  return 0.0;
}

/// Micromodulus of a 3D solid from its bulk modulus, c = 18 k / (pi delta^4) (Silling & Askari
/// 2005, eq. 17; the form paper 000 uses for reinforced concrete, after Miranda et al. 2018).
inline double pd_micromodulus_from_bulk(double k, double delta) {
  return 18.0 * k / (M_PI * std::pow(delta, 4));
}

/// Critical stretch from the fracture energy G0 (energy per crack area), by integrating the
/// work of the bonds that a crack surface cuts:
///   3D:            s0 = sqrt(5 G0 / (6 E delta))         (Silling & Askari 2005, eq. 24)
///   plane stress:  s0 = sqrt(4 pi G0 / (9 E delta))      (Madenci & Oterkus 2014, sec. 2.7)
///   plane strain:  s0 = sqrt(5 pi G0 / (12 E delta))     (paper 000 eq. 7)
inline double pd_critical_stretch(PdDimension d, double E, double G0, double delta) {
  switch (d) {
  case PdDimension::Solid3D:
    return std::sqrt(5.0 * G0 / (6.0 * E * delta));
  case PdDimension::PlaneStress:
    return std::sqrt(4.0 * M_PI * G0 / (9.0 * E * delta));
  case PdDimension::PlaneStrain:
    return std::sqrt(5.0 * M_PI * G0 / (12.0 * E * delta));
  }
  return 0.0;
}

/// Critical stretch of a 3D bond with micromodulus c: the same energy balance written with c,
/// s0 = sqrt(10 G0 / (pi c delta^5)) (paper 000 eq. 7-b, where the printed delta^4 is a
/// dimensional slip; with c = 18 k / (pi delta^4) it gives Silling & Askari's sqrt(5 G0 / (9 k
/// delta))).
inline double pd_critical_stretch_from_c(double c, double G0, double delta) {
  return std::sqrt(10.0 * G0 / (M_PI * c * std::pow(delta, 5)));
}

/// One bond law: prototype microelastic brittle (PMB) or micro-plastic (elastic-perfectly
/// plastic in the bond stretch, Macek & Silling 2007), with an optional critical stretch.
struct BondLaw {
  double c = 0.0;                // micromodulus
  double critical_stretch = 0.0; // s0; 0: the bond never breaks
  double yield_stretch = 0.0;    // s_Y of the micro-plastic bond; 0: PMB (elastic)
  double alpha = 0.0;            // LAMMPS peri/pmb rule: s0_i = s00 - alpha * min_j s_ij
  bool breaks() const { return critical_stretch > 0.0; }
  bool plastic() const { return yield_stretch > 0.0; }
};

/// Force density magnitude c (s - s_p) of an intact bond, with the plastic stretch updated in
/// place (micro-plastic: |s - s_p| <= s_Y, the return to the yield stretch is exact).
inline double bond_force(const BondLaw& law, double stretch, double& plastic_stretch) {
  if (law.plastic()) {
    const double elastic = stretch - plastic_stretch;
    if (elastic > law.yield_stretch)
      plastic_stretch = stretch - law.yield_stretch;
    else if (elastic < -law.yield_stretch)
      plastic_stretch = stretch + law.yield_stretch;
  }
  return law.c * (stretch - plastic_stretch);
}

/// Energy per unit volume squared stored in a bond of initial length xi: w = c (s - s_p)^2 xi / 2
/// (the pair potential of the PMB model; the plastic part has been dissipated).
inline double bond_energy(const BondLaw& law, double stretch, double plastic_stretch, double xi) {
  const double e = stretch - plastic_stretch;
  return 0.5 * law.c * e * e * xi;
}

} // namespace mf::materials
