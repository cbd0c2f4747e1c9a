#pragma once
// The constitutive models of the Galerkin solvers (and the strength of an SPH solid), chosen by
// name under a material's `plasticity: {model: ...}`: given a total strain and the committed
// history, the stress, its consistent tangent and the trial history.
//
// One model is one alternative of ConstitutiveModel and one file of its own (j2_plasticity,
// drucker_prager); the dispatch is a std::visit per point, no virtual call. Plane strain is the
// 3D update at eps_zz = 0. Plane stress is J2's projected return where the model is J2, and for
// any other model a local Newton iteration on eps_zz to sigma_zz = 0 with the tangent condensed
// (D_ab - D_az D_zb / D_zz), the plane-stress enforcement at the Gauss point of de Souza Neto,
// Peric & Owen 2008, ch. 9.
#include "meshfree/materials/drucker_prager.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include <string>
#include <variant>

namespace mf::materials {

using ConstitutiveModel = std::variant<J2Parameters, DruckerPragerParameters>;

/// The model's name as the input gives it: j2, drucker_prager.
std::string model_name(const ConstitutiveModel& m);

/// The model's elastic constants.
IsotropicElastic elasticity(const ConstitutiveModel& m);

/// The same model with other elastic constants.
void set_elasticity(ConstitutiveModel& m, const IsotropicElastic& e);

StressUpdate3D stress_update_3d(const ConstitutiveModel& m, const Vec6& strain,
                                const MaterialState& committed);
StressUpdate2D stress_update_plane(const ConstitutiveModel& m, PlaneModel model, const Vec3& strain,
                                   const MaterialState& committed);

/// Whether the model's consistent tangent is symmetric (Drucker-Prager's only with associated
/// flow, eta_bar = eta).
bool symmetric_tangent(const ConstitutiveModel& m);

/// A strength of the model's scale: J2's initial yield stress, Drucker-Prager's xi c0 (the
/// cone's sqrt(J2) at zero mean stress; 1 for a cohesionless soil).
double reference_strength(const ConstitutiveModel& m);

/// The model's strength as its input gives it, for the plausibility checks of units: the key
/// under `plasticity:` and its value (J2's yield_stress, Drucker-Prager's cohesion).
struct StrengthInput {
  const char* key = "";
  double value = 0.0;
};
StrengthInput strength_input(const ConstitutiveModel& m);

/// How far a stress is towards first yield from a virgin state, on the scale of
/// reference_strength: the factor lambda with which lambda * stress reaches the yield surface is
/// reference_strength / first_yield_measure (J2: the von Mises stress scaled by sigma_ref /
/// sigma0; Drucker-Prager: the larger of (sqrt(J2) + eta p) / (xi c0) and p / T, times
/// sigma_ref).
double first_yield_measure(const ConstitutiveModel& m, const Vec6& stress, double sigma_ref);

/// Plane stress by a local Newton iteration on eps_zz of any 3D update (the model's own
/// projected return is faster where it has one).
StressUpdate2D plane_stress_by_iteration(const ConstitutiveModel& m, const Vec3& strain,
                                         const MaterialState& committed);

} // namespace mf::materials
