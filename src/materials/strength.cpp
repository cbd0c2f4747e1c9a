#include "meshfree/materials/strength.hpp"
#include <algorithm>

namespace mf::materials {

double shear_modulus(const StrengthModel& m, double rho) {
  return std::visit([rho](const auto& law) { return shear_modulus(law, rho); }, m);
}

double current_yield(const StrengthModel& m, double pressure, double alpha, double damage,
                     double strain_rate) {
  return std::visit(
      [&](const auto& law) { return current_yield(law, pressure, alpha, damage, strain_rate); }, m);
}

double hjc_damage_increment(const Hjc& h, double rho, double rho_max, double pressure,
                            double dalpha) {
  const double mu = rho / h.rho0 - 1.0, mu_max = rho_max / h.rho0 - 1.0;
  const double dmu = mu > mu_max && mu > h.mu_crush ? mu - std::max(mu_max, h.mu_crush) : 0.0;
  return (dalpha + dmu) / hjc_fracture_strain(h, pressure);
}

} // namespace mf::materials
