#pragma once
// The equation of state of a material in explicit hydrodynamics: one of the parameter sets of
// materials/eos.hpp and materials/geomaterials.hpp. A solver dispatches on it once per material
// (std::visit) and evaluates pressure_and_sound for each of that material's particles. Compaction
// and HJC depend on the largest density a particle has reached (rho_max), HJC on its damage too.
#include "meshfree/materials/eos.hpp"
#include "meshfree/materials/geomaterials.hpp"
#include <algorithm>
#include <optional>
#include <variant>

namespace mf::materials {

/// A JWL explosive: its detonation products and, optionally, the unreacted explosive
/// (Mie-Grueneisen on the JWL's rho0). The unreacted share carries the pressure share 1 - F of
/// the burn fraction F, so that the front is a ZND wave whose speed and CJ state follow from the
/// two equations of state.
struct JwlExplosive {
  Jwl jwl;
  std::optional<MieGruneisen> unreacted;
};

using EquationOfState =
    std::variant<IdealGas, JwlExplosive, MieGruneisen, LinearPolynomial, Compaction, Hjc>;

/// Pressure and squared sound speed of each equation of state at density rho, specific energy e,
/// largest density reached rho_max and damage D (each law takes the arguments it depends on).
inline PressureAndSound pressure_and_sound(const IdealGas& g, double rho, double e, double,
                                           double) {
  return ideal_gas(g, rho, e);
}
inline PressureAndSound pressure_and_sound(const MieGruneisen& m, double rho, double e, double,
                                           double) {
  return mie_gruneisen(m, rho, e);
}
inline PressureAndSound pressure_and_sound(const LinearPolynomial& l, double rho, double e, double,
                                           double) {
  return linear_polynomial(l, rho, e);
}
inline PressureAndSound pressure_and_sound(const Compaction& c, double rho, double, double rho_max,
                                           double) {
  return compaction(c, rho, rho_max);
}
inline PressureAndSound pressure_and_sound(const Hjc& h, double rho, double, double rho_max,
                                           double damage) {
  return hjc_pressure(h, rho, rho_max, damage);
}

/// A JWL explosive at burn fraction F: F times the products' pressure, plus (1 - F) times the
/// unreacted explosive's when it has one. The unreacted share follows its own Hugoniot with the
/// energy gained above the initial state (e - e0): a shock into the explosive (the von Neumann
/// spike), then the burn. The sound speed is the larger of the two, so that the unburnt explosive
/// keeps the products' speed and the step resolves the burn.
inline PressureAndSound explosive_pressure(const JwlExplosive& x, double rho, double e,
                                           double burn_fraction) {
  const PressureAndSound products = jwl(x.jwl, rho, e);
  PressureAndSound out{burn_fraction * products.p, products.c2};
  if (x.unreacted) {
    const PressureAndSound u = mie_gruneisen(*x.unreacted, rho, e - x.jwl.e0);
    out.p += (1.0 - burn_fraction) * u.p;
    out.c2 = std::max(out.c2, u.c2);
  }
  return out;
}

} // namespace mf::materials
