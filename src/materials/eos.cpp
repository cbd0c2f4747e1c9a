#include "meshfree/materials/eos.hpp"
#include <cmath>

namespace mf::materials {

PressureAndSound ideal_gas(const IdealGas& g, double rho, double e) {
  const double p = (g.gamma - 1.0) * rho * e;
  return {p, rho > 0.0 ? g.gamma * p / rho : 0.0};
}

PressureAndSound jwl(const Jwl& j, double rho, double e) {
  const double V = j.rho0 / rho, w = j.omega;
  const double e1 = std::exp(-j.R1 * V), e2 = std::exp(-j.R2 * V);
  const double p =
      j.A * (1.0 - w / (j.R1 * V)) * e1 + j.B * (1.0 - w / (j.R2 * V)) * e2 + w * rho * e;
  // dp/dV at fixed e, from d/dV [(1 - w/(R V)) exp(-R V)] = exp(-R V) (w/(R V^2) - R + w/V).
  const double dp_dV = j.A * e1 * (w / (j.R1 * V * V) - j.R1 + w / V) +
                       j.B * e2 * (w / (j.R2 * V * V) - j.R2 + w / V);
  const double dp_drho_e = dp_dV * (-V / rho) + w * e; // dV/drho = -V/rho
  const double dp_de_rho = w * rho;
  return {p, dp_drho_e + p / (rho * rho) * dp_de_rho};
}

PressureAndSound mie_gruneisen(const MieGruneisen& m, double rho, double e) {
  const double mu = rho / m.rho0 - 1.0, k = m.rho0 * m.c0 * m.c0;
  double p, dp_dmu;
  if (mu > 0.0) {
    const double a = 1.0 + (1.0 - 0.5 * m.gamma0) * mu, b = 1.0 - (m.s - 1.0) * mu;
    p = k * mu * a / (b * b);
    // d/dmu [mu a / b^2] = (a + mu (1 - Gamma0/2)) / b^2 + 2 (s - 1) mu a / b^3.
    dp_dmu = k * ((a + mu * (1.0 - 0.5 * m.gamma0)) / (b * b) +
                  2.0 * (m.s - 1.0) * mu * a / (b * b * b));
  } else {
    p = k * mu;
    dp_dmu = k;
  }
  p += m.gamma0 * m.rho0 * e;
  const double dp_drho_e = dp_dmu / m.rho0, dp_de_rho = m.gamma0 * m.rho0;
  return {p, dp_drho_e + p / (rho * rho) * dp_de_rho};
}

PressureAndSound linear_polynomial(const LinearPolynomial& l, double rho, double e) {
  const double mu = rho / l.rho0 - 1.0;
  const double* c = l.c;
  const double E = l.rho0 * e;
  const double p =
      c[0] + mu * (c[1] + mu * (c[2] + mu * c[3])) + (c[4] + mu * (c[5] + mu * c[6])) * E;
  const double dp_dmu = c[1] + mu * (2.0 * c[2] + 3.0 * mu * c[3]) + (c[5] + 2.0 * mu * c[6]) * E;
  const double dp_de_rho = (c[4] + mu * (c[5] + mu * c[6])) * l.rho0;
  return {p, dp_dmu / l.rho0 + p / (rho * rho) * dp_de_rho};
}

} // namespace mf::materials
