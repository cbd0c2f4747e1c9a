#pragma once
// A material of an SPH run: its equation of state and its strength (materials/).
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/strength.hpp"
#include <string>
#include <variant>

namespace mf::sph {

/// A particle fails when its plastic strain reaches failure_strain (> 0) or its HJC damage
/// reaches 1: it then carries no deviatoric stress and no tension (it flows as a crushed,
/// cohesionless material).
struct Material {
  std::string name;
  materials::EquationOfState eos = materials::IdealGas{};
  materials::StrengthModel strength = materials::NoStrength{};
  double failure_strain = 0.0; // 0: no failure by plastic strain
  /// Whether the material carries deviatoric stress.
  bool solid() const { return !std::holds_alternative<materials::NoStrength>(strength); }
};

} // namespace mf::sph
