#include "meshfree/materials/geomaterials.hpp"
#include <algorithm>
#include <cmath>

namespace mf::materials {

namespace {
/// The segment k with x[k] <= at < x[k+1], clamped to the table.
std::size_t segment(const std::vector<double>& x, double at) {
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  const std::size_t k = static_cast<std::size_t>(it - x.begin());
  return std::clamp<std::size_t>(k, 1, x.size() - 1) - 1;
}
} // namespace

double PiecewiseLinear::operator()(double at) const {
  if (x.size() == 1 || at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const std::size_t k = segment(x, at);
  const double t = (at - x[k]) / (x[k + 1] - x[k]);
  return y[k] + t * (y[k + 1] - y[k]);
}

double PiecewiseLinear::slope(double at) const {
  if (x.size() == 1 || at < x.front() || at > x.back()) return 0.0;
  const std::size_t k = segment(x, at);
  return (y[k + 1] - y[k]) / (x[k + 1] - x[k]);
}

PressureAndSound compaction(const Compaction& m, double rho, double rho_max) {
  const double top = std::max(rho, rho_max);
  const double c = m.sound_speed(top);
  double p = rho >= rho_max ? m.loading(rho) : m.loading(rho_max) + c * c * (rho - rho_max);
  p = std::max(p, -m.tensile_limit);
  return {p, c * c};
}

double granular_yield(const GranularStrength& g, double pressure) {
  return pressure > 0.0 ? std::max(g.yield(pressure), 0.0) : 0.0;
}

double hjc_grain_compression(const Hjc& m) {
  // Solve K1 x + K2 x^2 + K3 x^3 = P_lock for its smallest positive root by Newton from the
  // linear estimate; then mu_lock - mu_grain = x (1 + mu_grain).
  double x = m.P_lock / m.K1;
  for (int it = 0; it < 50; ++it) {
    const double f = x * (m.K1 + x * (m.K2 + x * m.K3)) - m.P_lock;
    const double df = m.K1 + x * (2.0 * m.K2 + 3.0 * x * m.K3);
    const double dx = f / df;
    x -= dx;
    if (std::abs(dx) < 1e-15) break;
  }
  return (m.mu_lock - x) / (1.0 + x);
}

PressureAndSound hjc_pressure(const Hjc& m, double rho, double rho_max, double damage) {
  const double mu = rho / m.rho0 - 1.0;
  const double mu_max = std::max(mu, rho_max / m.rho0 - 1.0);
  const double K_elastic = m.P_crush / m.mu_crush;
  double p, K;
  if (mu_max <= m.mu_crush) {
    // Elastic region, loading and unloading alike.
    p = K_elastic * mu;
    K = K_elastic;
  } else if (mu_max <= m.mu_lock) {
    // Compaction: linear from the crush point to the lock point on loading; unloading with a
    // modulus interpolated between the elastic and the dense ones by the compaction reached.
    const double F = (mu_max - m.mu_crush) / (m.mu_lock - m.mu_crush);
    const double p_max =
        m.P_crush + (m.P_lock - m.P_crush) * (mu_max - m.mu_crush) / (m.mu_lock - m.mu_crush);
    K = (1.0 - F) * K_elastic + F * m.K1;
    p = p_max - K * (mu_max - mu);
  } else {
    // Fully dense: reversible along the dense curve.
    const double mu_grain = hjc_grain_compression(m);
    const double x = (mu - mu_grain) / (1.0 + mu_grain);
    p = x * (m.K1 + x * (m.K2 + x * m.K3));
    K = (m.K1 + x * (2.0 * m.K2 + 3.0 * x * m.K3)) / (1.0 + mu_grain);
  }
  p = std::max(p, -m.T * (1.0 - std::clamp(damage, 0.0, 1.0)));
  // dp/drho = K / rho0; the sound speed uses the unloading (stiffest) modulus.
  return {p, std::max(K, K_elastic) / m.rho0};
}

double hjc_yield(const Hjc& m, double pressure, double damage, double eps_dot) {
  const double D = std::clamp(damage, 0.0, 1.0);
  const double p_star = pressure / m.fc, t_star = m.T / m.fc;
  double s;
  if (p_star >= 0.0) {
    s = m.A * (1.0 - D) + m.B * std::pow(p_star, m.N);
  } else {
    const double reach = t_star * (1.0 - D);
    s = reach > 0.0 ? m.A * (1.0 - D) * std::max(0.0, 1.0 + p_star / reach) : 0.0;
  }
  const double rate = std::max(eps_dot / m.eps_dot0, 1.0);
  s *= 1.0 + m.C * std::log(rate);
  return std::min(s, m.s_max) * m.fc;
}

double hjc_fracture_strain(const Hjc& m, double pressure) {
  const double sum = std::max(pressure / m.fc + m.T / m.fc, 0.0);
  return std::max(m.D1 * std::pow(sum, m.D2), m.eps_f_min);
}

} // namespace mf::materials
