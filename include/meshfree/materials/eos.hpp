#pragma once
// Equations of state p(rho, e) for explicit hydrodynamics, as pure functions of the density rho
// [kg/m^3] and the specific internal energy e [J/kg], each with its adiabatic sound speed
// c^2 = dp/drho|_e + p / rho^2 dp/de|_rho.

namespace mf::materials {

struct PressureAndSound {
  double p = 0.0;  // pressure [Pa]
  double c2 = 0.0; // squared adiabatic sound speed [m^2/s^2]
};

/// Ideal gas: p = (gamma - 1) rho e, c^2 = gamma p / rho.
struct IdealGas {
  double gamma = 1.4;
};
PressureAndSound ideal_gas(const IdealGas& g, double rho, double e);

/// Jones-Wilkins-Lee detonation products (Lee, Hornig & Kury 1968):
///   p = A (1 - w/(R1 V)) exp(-R1 V) + B (1 - w/(R2 V)) exp(-R2 V) + w rho e,  V = rho0 / rho.
/// TNT (Dobratz & Crawford 1985, LLNL Explosives Handbook UCRL-52997): rho0 = 1630 kg/m^3,
/// A = 373.77 GPa, B = 3.7471 GPa, R1 = 4.15, R2 = 0.90, w = 0.35, D = 6930 m/s,
/// P_CJ = 21 GPa, E0 = 6.0 GJ/m^3 (e0 = E0 / rho0).
struct Jwl {
  double rho0 = 1630.0, A = 373.77e9, B = 3.7471e9, R1 = 4.15, R2 = 0.90, omega = 0.35;
  double detonation_speed = 6930.0; // D_CJ [m/s]
  double cj_pressure = 21.0e9;      // P_CJ [Pa], for reference
  double e0 = 6.0e9 / 1630.0;       // specific detonation energy [J/kg]
};
PressureAndSound jwl(const Jwl& j, double rho, double e);

/// Mie-Grueneisen with a linear shock Hugoniot U_s = c0 + s u_p (the form of LS-DYNA's
/// *EOS_GRUNEISEN and AUTODYN's "Shock" EOS), mu = rho/rho0 - 1:
///   mu > 0: p = rho0 c0^2 mu (1 + (1 - Gamma0/2) mu) / (1 - (s - 1) mu)^2 + Gamma0 rho0 e
///   mu <= 0: p = rho0 c0^2 mu + Gamma0 rho0 e.
struct MieGruneisen {
  double rho0 = 0.0, c0 = 0.0, s = 0.0, gamma0 = 0.0;
};
PressureAndSound mie_gruneisen(const MieGruneisen& m, double rho, double e);

/// Linear polynomial (LS-DYNA *EOS_LINEAR_POLYNOMIAL), mu = rho/rho0 - 1:
///   p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) rho0 e.
/// A linear elastic solid is C1 = K, the rest 0.
struct LinearPolynomial {
  double rho0 = 0.0;
  double c[7] = {0, 0, 0, 0, 0, 0, 0};
};
PressureAndSound linear_polynomial(const LinearPolynomial& l, double rho, double e);

} // namespace mf::materials
