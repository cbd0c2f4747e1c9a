#pragma once
// Geomaterials for explicit blast analyses, as pure functions of the current state and the
// history a particle carries (its largest density so far, its damage):
//  - a tabulated compaction equation of state for porous soil (AUTODYN's "Compaction" EOS,
//    LS-DYNA's *EOS_TABULATED_COMPACTION): a plastic loading curve p(rho) and an elastic
//    unloading sound speed c(rho_max);
//  - a pressure-dependent yield stress Y(p) for granular soil (AUTODYN's piecewise
//    Drucker-Prager / "MO granular" strength), with a shear modulus that may follow the density;
//  - the Holmquist-Johnson-Cook concrete model (Holmquist, Johnson & Cook 1993, "A computational
//    constitutive model for concrete subjected to large strains, high strain rates, and high
//    pressures", 14th Int. Symp. on Ballistics, Quebec): its three-part equation of state,
//    its normalised strength surface with strain-rate enhancement, and its damage.
#include "meshfree/materials/eos.hpp"
#include <vector>

namespace mf::materials {

/// A piecewise-linear function y(x) on ascending abscissae, constant beyond its ends.
struct PiecewiseLinear {
  std::vector<double> x, y;
  double operator()(double at) const;
  double slope(double at) const; // of the segment holding `at` (0 beyond the ends)
};

/// Tabulated compaction of a porous solid. While the density is at its largest so far the state
/// follows the loading curve p = P(rho); below it, it unloads and reloads elastically with the
/// bulk sound speed reached, p = P(rho_max) + c(rho_max)^2 (rho - rho_max). The pressure is not
/// allowed below -tensile_limit (0: a granular medium carries no tension). The internal energy
/// does not enter.
struct Compaction {
  PiecewiseLinear loading;     // density [kg/m^3] -> pressure [Pa]
  PiecewiseLinear sound_speed; // density [kg/m^3] -> elastic bulk sound speed [m/s]
  double tensile_limit = 0.0;
};
PressureAndSound compaction(const Compaction& m, double rho, double rho_max);

/// Pressure-dependent yield of a granular solid: von Mises equivalent stress limited to Y(p),
/// Y = 0 at and below zero pressure (no cohesion in tension).
struct GranularStrength {
  PiecewiseLinear yield;         // pressure [Pa] -> yield stress [Pa]
  PiecewiseLinear shear_modulus; // density [kg/m^3] -> G [Pa]; a single point gives a constant
};
double granular_yield(const GranularStrength& g, double pressure);

/// Holmquist-Johnson-Cook concrete. Defaults: the 48 MPa concrete of the 1993 paper.
struct Hjc {
  // Strength: sigma* = [A (1 - D) + B P*^N] [1 + C ln(eps_dot*)] <= s_max, starred quantities
  // normalised by f_c (stresses) and eps_dot_0 (rates).
  double A = 0.79, B = 1.60, N = 0.61, C = 0.007, s_max = 7.0;
  double fc = 48.0e6, T = 4.0e6, eps_dot0 = 1.0;
  // Damage: D = sum (d eps_p + d mu_p) / max(D1 (P* + T*)^D2, eps_f_min).
  double D1 = 0.04, D2 = 1.0, eps_f_min = 0.01;
  // Equation of state: elastic to (mu_crush, P_crush), linear compaction to (mu_lock, P_lock),
  // then the fully dense curve K1 m + K2 m^2 + K3 m^3, m = (mu - mu_grain)/(1 + mu_grain).
  double rho0 = 2440.0, P_crush = 16.0e6, mu_crush = 0.001, K1 = 85.0e9, K2 = -171.0e9,
         K3 = 208.0e9, P_lock = 0.8e9, mu_lock = 0.10;
  double shear_modulus = 14.86e9;
};

/// The HJC pressure at density rho after the largest density rho_max, with damage D: the
/// tension cut-off is -T (1 - D). c2 is the unloading bulk modulus over rho.
PressureAndSound hjc_pressure(const Hjc& m, double rho, double rho_max, double damage);

/// mu_grain: the excess compression where the fully dense curve has zero pressure, chosen so that
/// the curve passes through (mu_lock, P_lock) (the paper's "mu_lock = rho_grain / rho_0 - 1").
double hjc_grain_compression(const Hjc& m);

/// The HJC equivalent yield stress [Pa] at pressure p with damage D and equivalent strain rate
/// eps_dot [1/s]. In tension the intact cohesion A (1 - D) falls linearly to zero at
/// p = -T (1 - D).
double hjc_yield(const Hjc& m, double pressure, double damage, double eps_dot);

/// The plastic strain to fracture at pressure p: max(D1 (P* + T*)^D2, eps_f_min).
double hjc_fracture_strain(const Hjc& m, double pressure);

} // namespace mf::materials
