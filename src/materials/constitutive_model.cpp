#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::materials {

std::string model_name(const ConstitutiveModel& m) {
  return std::holds_alternative<J2Parameters>(m) ? "j2" : "drucker_prager";
}

IsotropicElastic elasticity(const ConstitutiveModel& m) {
  return std::visit([](const auto& p) { return IsotropicElastic{p.E, p.nu}; }, m);
}

void set_elasticity(ConstitutiveModel& m, const IsotropicElastic& e) {
  std::visit(
      [&](auto& p) {
        p.E = e.E;
        p.nu = e.nu;
      },
      m);
}

bool symmetric_tangent(const ConstitutiveModel& m) {
  const auto* dp = std::get_if<DruckerPragerParameters>(&m);
  return !dp || dp->eta_bar == dp->eta;
}

double reference_strength(const ConstitutiveModel& m) {
  if (const auto* j2 = std::get_if<J2Parameters>(&m)) return j2->sigma0;
  const auto& dp = std::get<DruckerPragerParameters>(m);
  // A cohesionless soil has no strength of its own: any scale serves a relative measure.
  return dp.cohesion > 0.0 ? dp.xi * dp.cohesion : 1.0;
}

StrengthInput strength_input(const ConstitutiveModel& m) {
  if (const auto* j2 = std::get_if<J2Parameters>(&m)) return {"yield_stress", j2->sigma0};
  return {"cohesion", std::get<DruckerPragerParameters>(m).cohesion};
}

double first_yield_measure(const ConstitutiveModel& m, const Vec6& stress, double sigma_ref) {
  if (const auto* j2 = std::get_if<J2Parameters>(&m)) {
    // A plane state's von Mises stress by the plane formula the plane outputs report.
    const bool plane = stress(3) == 0.0 && stress(4) == 0.0;
    const double vm =
        plane ? von_mises(Vec3(stress(0), stress(1), stress(5)), stress(2)) : von_mises_3d(stress);
    return vm * (sigma_ref / j2->sigma0);
  }
  const auto& dp = std::get<DruckerPragerParameters>(m);
  const double p = stress.head<3>().sum() / 3.0;
  const double J = voigt::tensor_norm(voigt::deviator(stress)) / std::sqrt(2.0);
  const double shear = J + dp.eta * p;
  double ratio = dp.cohesion > 0.0 ? shear / (dp.xi * dp.cohesion)
                 : shear > 0.0     ? std::numeric_limits<double>::infinity()
                                   : 0.0;
  if (std::isfinite(dp.tension_cutoff) && p > 0.0)
    ratio = std::max(ratio, dp.tension_cutoff > 0.0 ? p / dp.tension_cutoff
                                                    : std::numeric_limits<double>::infinity());
  return ratio * sigma_ref;
}

StressUpdate3D stress_update_3d(const ConstitutiveModel& m, const Vec6& strain,
                                const MaterialState& committed) {
  if (const auto* j2 = std::get_if<J2Parameters>(&m)) return j2_update_3d(*j2, strain, committed);
  return drucker_prager_update_3d(std::get<DruckerPragerParameters>(m), strain, committed);
}

StressUpdate2D plane_stress_by_iteration(const ConstitutiveModel& m, const Vec3& strain,
                                         const MaterialState& committed) {
  // Start from the elastic eps_zz of the committed plastic strain; Newton on sigma_zz(eps_zz)
  // with the update's own tangent D_zz (the step's exact derivative).
  const IsotropicElastic e = elasticity(m);
  const Vec6& ep = committed.plastic_strain;
  double ezz = ep(2) - e.nu / (1.0 - e.nu) * (strain(0) - ep(0) + strain(1) - ep(1));
  for (int it = 0;; ++it) {
    const StressUpdate3D r3 = stress_update_3d(m, voigt::embed(strain, ezz), committed);
    const double szz = r3.stress(2), dzz = r3.tangent(2, 2);
    if (std::abs(szz) <= 1e-13 * r3.stress.cwiseAbs().maxCoeff()) {
      StressUpdate2D r = voigt::reduce(r3, ezz);
      if (dzz != 0.0)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            r.tangent(a, b) -= r3.tangent(kPlane[a], 2) * r3.tangent(2, kPlane[b]) / dzz;
      r.stress_zz = 0.0;
      return r;
    }
    if (!(dzz > 0.0) || it == 50)
      fail("plane-stress iteration of the ", model_name(m), " model did not converge (sigma_zz ",
           szz, " after ", it, " iterations, d sigma_zz / d eps_zz ", dzz, ")");
    ezz -= szz / dzz;
  }
}

StressUpdate2D stress_update_plane(const ConstitutiveModel& m, PlaneModel model, const Vec3& strain,
                                   const MaterialState& committed) {
  if (const auto* j2 = std::get_if<J2Parameters>(&m))
    return model == PlaneModel::PlaneStrain ? j2_update_plane_strain(*j2, strain, committed)
                                            : j2_update_plane_stress(*j2, strain, committed);
  if (model == PlaneModel::PlaneStrain)
    return voigt::reduce(stress_update_3d(m, voigt::embed(strain, 0.0), committed), 0.0);
  return plane_stress_by_iteration(m, strain, committed);
}

} // namespace mf::materials
