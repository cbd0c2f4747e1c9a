#pragma once
// Strength of a solid in explicit hydrodynamics: the deviatoric stress S follows the Jaumann rate
// dS/dt = 2 G (D - tr(D) I / 3) + W S - S W (D, W: symmetric and skew parts of grad v) and is
// returned radially to the yield surface of its model after each update:
//  - ElasticShear: no yield;
//  - VonMises: the J2 return of materials/j2_plasticity with its isotropic and kinematic
//    hardening (the same update as the Galerkin solver's);
//  - GranularStrength: a pressure-dependent yield Y(p) and a shear modulus G(rho) (soil);
//  - Hjc: the Holmquist-Johnson-Cook surface with damage (concrete);
//  - DruckerPragerShear: the Galerkin solver's Drucker-Prager cone (materials/drucker_prager)
//    at the equation of state's pressure, the deviator returned to it alone (the volumetric
//    response, and with it the dilatancy, is the equation of state's).
// The pressure comes from the equation of state. A solver dispatches on the model once per
// material (std::visit) and calls these pure functions for each of that material's particles.
#include "meshfree/materials/drucker_prager.hpp"
#include "meshfree/materials/geomaterials.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include <algorithm>
#include <cmath>
#include <variant>

namespace mf::materials {

/// A fluid: no deviatoric stress.
struct NoStrength {};

/// An elastic solid without yield.
struct ElasticShear {
  double shear_modulus = 0.0;
};

/// A von Mises solid. Its J2 parameters hold E = 2G and nu = 0, so that the return's shear
/// modulus is G; the volumetric response is the equation of state's.
struct VonMises {
  double shear_modulus = 0.0;
  J2Parameters j2;
};

/// A Drucker-Prager solid: shear modulus G = E / (2 (1 + nu)) of its parameters.
struct DruckerPragerShear {
  double shear_modulus = 0.0;
  DruckerPragerParameters dp;
};

using StrengthModel =
    std::variant<NoStrength, ElasticShear, VonMises, GranularStrength, Hjc, DruckerPragerShear>;

/// The shear modulus of each model at density rho.
inline double shear_modulus(const NoStrength&, double) {
  return 0.0;
}
inline double shear_modulus(const ElasticShear& m, double) {
  return m.shear_modulus;
}
inline double shear_modulus(const VonMises& m, double) {
  return m.shear_modulus;
}
inline double shear_modulus(const GranularStrength& g, double rho) {
  return g.shear_modulus(rho);
}
inline double shear_modulus(const Hjc& h, double) {
  return h.shear_modulus;
}
inline double shear_modulus(const DruckerPragerShear& m, double) {
  return m.shear_modulus;
}
double shear_modulus(const StrengthModel& m, double rho);

/// The current yield stress of each model at pressure p, equivalent plastic strain alpha, damage
/// D and equivalent strain rate eps_dot [1/s] (0 for a model without plasticity).
inline double current_yield(const NoStrength&, double, double, double, double) {
  return 0.0;
}
inline double current_yield(const ElasticShear&, double, double, double, double) {
  return 0.0;
}
inline double current_yield(const VonMises& m, double, double alpha, double, double) {
  return yield_stress(m.j2, alpha);
}
inline double current_yield(const GranularStrength& g, double pressure, double, double, double) {
  return granular_yield(g, pressure);
}
inline double current_yield(const Hjc& h, double pressure, double, double damage,
                            double strain_rate) {
  return hjc_yield(h, pressure, damage, strain_rate);
}
/// The cone's von Mises stress at the pressure p (compression positive: the mean stress is -p),
/// sqrt 3 (xi c(alpha) + eta p), and zero beyond the apex.
inline double current_yield(const DruckerPragerShear& m, double pressure, double alpha, double,
                            double) {
  const DruckerPragerParameters& d = m.dp;
  return std::max(0.0,
                  std::sqrt(3.0) * (d.xi * (d.cohesion + d.hardening * alpha) + d.eta * pressure));
}
double current_yield(const StrengthModel& m, double pressure, double alpha, double damage,
                     double strain_rate);

/// Perfectly plastic radial return at a given yield stress Y (pressure-dependent models): a
/// deviator of von Mises stress q > Y is scaled by Y / q, with the plastic strain increment
/// (q - Y) / 3G (Wilkins 1964).
struct YieldReturn {
  bool plastic = false;
  double scale = 1.0, dalpha = 0.0;
};
inline YieldReturn perfectly_plastic_return(double q, double Y, double G) {
  YieldReturn r;
  if (q > Y) {
    r.plastic = true;
    r.scale = q > 0.0 ? Y / q : 0.0;
    r.dalpha = (q - Y) / (3.0 * G);
  }
  return r;
}

/// The increment of a model's hardening variable alpha in such a return: the equivalent plastic
/// strain (q - Y) / 3G of the von Mises-type surfaces; the Drucker-Prager cone's own
/// alpha' = xi dgamma, the return shrinking sqrt(J2) = q / sqrt 3 by G dgamma, so that a preload's
/// alpha goes on in the same measure: xi (q - Y) / (sqrt 3 G) = sqrt 3 xi dalpha.
template <class Law> double alpha_increment(const Law&, const YieldReturn& r) {
  return r.dalpha;
}
inline double alpha_increment(const DruckerPragerShear& m, const YieldReturn& r) {
  return std::sqrt(3.0) * m.dp.xi * r.dalpha;
}

/// The HJC damage increment of a step (Holmquist, Johnson & Cook 1993): the plastic strain
/// increment plus the plastic volumetric compaction (the growth of the largest compression
/// mu = rho / rho0 - 1 beyond the crush point) over the strain to fracture at pressure p.
double hjc_damage_increment(const Hjc& h, double rho, double rho_max, double pressure,
                            double dalpha);

} // namespace mf::materials
