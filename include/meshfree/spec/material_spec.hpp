#pragma once
// One entry of a problem file's `materials:` list: elastic constants, density, and the optional
// parts each analysis takes what it needs from (plasticity for the Galerkin solver and SPH
// solids, an equation of state and a strength model for SPH, bond parameters for peridynamics).
#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/geomaterials.hpp"
#include "meshfree/materials/pd_state.hpp"
#include <optional>
#include <string>

namespace mf::spec {

/// A strength model other than J2 (which comes from `plasticity:`): a granular yield table and
/// shear modulus table (soil) or the Holmquist-Johnson-Cook model (concrete, constants from the
/// material's `hjc:`), and the plastic strain at which a particle fails (0: never).
struct StrengthSpec {
  enum class Model { J2, Granular, Hjc };
  Model model = Model::J2;
  materials::GranularStrength granular;
  double failure_strain = 0.0;
};

/// Peridynamic bond parameters (the micromodulus comes from E, the bulk modulus or is given).
/// law: lps is the state-based linear peridynamic solid (pd/state_based.hpp): its constants are
/// the material's E and nu (or bulk and shear moduli), the bonds give its breaking; law: eps is
/// the same with a yield stress (elastic-perfectly plastic, 3D).
struct BondSpec {
  bool microplastic = false;     // law: pmb | microplastic
  bool lps = false;              // law: lps, or law: eps (then yield_stress > 0)
  double yield_stress = 0.0;     // law: eps: the elastic-plastic LPS (Mitchell 2011)
  materials::Influence influence = materials::Influence::InverseLength; // lps only
  double micromodulus = 0.0;     // > 0: c given directly
  double fracture_energy = 0.0;  // > 0: critical stretch from G0
  double critical_stretch = 0.0; // > 0: given directly
  double yield_stretch = 0.0;    // > 0: micro-plastic bond
  double alpha = 0.0;            // LAMMPS rule
};

struct MaterialSpec {
  std::string name;
  std::string key_path;     // e.g. "materials[0]", for messages
  double E = 0.0, nu = 0.0; // 0: not given
  bool has_nu = false;
  double shear_modulus = 0.0; // given, or E / (2 (1 + nu)) from E and nu; 0: none
  double bulk_modulus = 0.0;  // given only
  double density = 0.0;       // 0: not given
  std::optional<materials::ConstitutiveModel> plasticity; // E and nu from above
  std::optional<materials::EquationOfState> eos;     // type hjc: the constants of `hjc:`
  std::optional<StrengthSpec> strength;
  std::optional<materials::Hjc> hjc;
  std::optional<BondSpec> bond;
};

} // namespace mf::spec
