#include "meshfree/sph/hydro.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include <algorithm>
#include <cmath>

namespace mf::sph {

materials::PressureAndSound evaluate(const Eos& eos, double rho, double e) {
  switch (eos.kind) {
  case Eos::Kind::IdealGas:
    return materials::ideal_gas(eos.ideal_gas, rho, e);
  case Eos::Kind::Jwl:
    return materials::jwl(eos.jwl, rho, e);
  case Eos::Kind::MieGruneisen:
    return materials::mie_gruneisen(eos.mie_gruneisen, rho, e);
  case Eos::Kind::LinearPolynomial:
    return materials::linear_polynomial(eos.linear_polynomial, rho, e);
  }
  return {};
}

void Particles::add(const double position[3], double m, double density, double energy,
                    double smoothing, int mat, bool is_fixed) {
  for (int d = 0; d < 3; ++d) {
    x.push_back(position[d]);
    v.push_back(0.0);
  }
  mass.push_back(m);
  rho.push_back(density);
  e.push_back(energy);
  h.push_back(smoothing);
  rho_ref.push_back(density);
  h_ref.push_back(smoothing);
  material.push_back(mat);
  light_time.push_back(-1.0);
  fixed.push_back(is_fixed ? 1 : 0);
  p.push_back(0.0);
  c.push_back(0.0);
}

void light_from_point(Hydro& s, const double at[3]) {
  Particles& P = s.particles;
  for (int i = 0; i < P.size(); ++i) {
    const Eos& eos = s.materials[P.material[i]].eos;
    if (eos.kind != Eos::Kind::Jwl) continue;
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d) r2 += (P.x[3 * i + d] - at[d]) * (P.x[3 * i + d] - at[d]);
    P.light_time[i] = std::sqrt(r2) / eos.jwl.detonation_speed;
  }
}

void update_state(Hydro& s) {
  Particles& P = s.particles;
  const int n = P.size();
  const double inv_dim = 1.0 / P.dim;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.h[i] = P.h_ref[i] * std::pow(P.rho_ref[i] / P.rho[i], inv_dim);
    const Eos& eos = s.materials[P.material[i]].eos;
    const materials::PressureAndSound ps = evaluate(eos, P.rho[i], P.e[i]);
    double f = 1.0;
    if (eos.kind == Eos::Kind::Jwl && P.light_time[i] >= 0.0) {
      // Burn fraction F = max(F_programmed, F_beta) (Wilkins 1964; LS-DYNA's
      // *MAT_HIGH_EXPLOSIVE_BURN): the lit time over the burn width, or the compression toward
      // the CJ state, (1 - V) / (1 - V_CJ) with 1 - V_CJ = P_CJ / (rho0 D^2).
      const materials::Jwl& j = eos.jwl;
      const double programmed =
          (s.time - P.light_time[i]) * j.detonation_speed / (s.settings.burn_width * P.h[i]);
      const double beta = (1.0 - j.rho0 / P.rho[i]) * j.rho0 * j.detonation_speed *
                          j.detonation_speed / j.cj_pressure;
      f = std::clamp(std::max(programmed, beta), 0.0, 1.0);
    } else if (eos.kind == Eos::Kind::Jwl) {
      f = 0.0; // never lit: inert
    }
    P.p[i] = f * ps.p;
    // The unburnt explosive keeps the products' sound speed so that the step resolves the burn.
    P.c[i] = std::sqrt(std::max(ps.c2, 0.0));
  }
}

void refresh_neighbours(Hydro& s) {
  const Particles& P = s.particles;
  const int n = P.size();
  const double skin = s.settings.skin;
  // A pair (i, j) left out at the last build was at least (h_i + h_j)(1 + skin) apart then; it
  // cannot interact yet while every particle has moved and grown its h by less than skin h.
  if (!s.x_at_build.empty()) {
    bool stale = false;
#pragma omp parallel for schedule(static) reduction(|| : stale)
    for (int i = 0; i < n; ++i) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double dx = P.x[3 * i + k] - s.x_at_build[3 * i + k];
        d2 += dx * dx;
      }
      const double grown = std::max(0.0, P.h[i] - s.h_at_build[i]);
      if (std::sqrt(d2) + grown > skin * s.h_at_build[i]) stale = true;
    }
    if (!stale) return;
  }
  const double h_max = *std::max_element(P.h.begin(), P.h.end());
  s.build_radius = 2.0 * h_max * (1.0 + skin);
  const neighbors::PairList all = neighbors::pairs_within(P.x, s.build_radius);
  // Keep the pairs within (h_i + h_j)(1 + skin): with smoothing lengths that differ across the
  // body, the global radius would hand small particles many far partners.
  s.pairs.offset.assign(n + 1, 0);
  s.pairs.partner.clear();
  for (int i = 0; i < n; ++i) {
    for (long k = all.offset[i]; k < all.offset[i + 1]; ++k) {
      const int j = all.partner[k];
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double dx = P.x[3 * i + d] - P.x[3 * j + d];
        r2 += dx * dx;
      }
      const double reach = (P.h[i] + P.h[j]) * (1.0 + skin);
      if (r2 < reach * reach) s.pairs.partner.push_back(j);
    }
    s.pairs.offset[i + 1] = static_cast<long>(s.pairs.partner.size());
  }
  s.x_at_build = P.x;
  s.h_at_build = P.h;
  ++s.rebuilds;
}

void compute_rates(const Hydro& s, Rates& r) {
  const Particles& P = s.particles;
  const Settings& S = s.settings;
  const int n = P.size(), dim = P.dim;
  r.dv.assign(3 * static_cast<std::size_t>(n), 0.0);
  r.drho.assign(n, 0.0);
  r.de.assign(n, 0.0);
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i) {
    const double pi_rho2 = P.p[i] / (P.rho[i] * P.rho[i]);
    double acc[3] = {0.0, 0.0, 0.0}, drho = 0.0, de = 0.0;
    for (long k = s.pairs.offset[i]; k < s.pairs.offset[i + 1]; ++k) {
      const int j = s.pairs.partner[k];
      double xij[3], vij[3], r2 = 0.0, vx = 0.0;
      for (int d = 0; d < 3; ++d) {
        xij[d] = P.x[3 * i + d] - P.x[3 * j + d];
        vij[d] = P.v[3 * i + d] - P.v[3 * j + d];
        r2 += xij[d] * xij[d];
        vx += vij[d] * xij[d];
      }
      const double hij = 0.5 * (P.h[i] + P.h[j]);
      if (r2 >= 4.0 * hij * hij || r2 == 0.0) continue;
      const double rr = std::sqrt(r2);
      // grad_i W_ij = dW/dr x_ij / r.
      const double g = kernels::cubic_spline_slope(dim, rr, hij) / rr;
      // Monaghan's viscosity for approaching pairs.
      double visc = 0.0;
      if (vx < 0.0) {
        const double mu = hij * vx / (r2 + S.phi * S.phi * hij * hij);
        const double cij = 0.5 * (P.c[i] + P.c[j]), rhoij = 0.5 * (P.rho[i] + P.rho[j]);
        visc = (-S.alpha * cij * mu + S.beta * mu * mu) / rhoij;
      }
      const double q = pi_rho2 + P.p[j] / (P.rho[j] * P.rho[j]) + visc;
      const double mj = P.mass[j];
      for (int d = 0; d < 3; ++d) acc[d] -= mj * q * g * xij[d];
      drho += mj * vx * g;
      de += 0.5 * mj * q * vx * g;
    }
    if (!P.fixed[i])
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = acc[d];
    r.drho[i] = drho;
    r.de[i] = de;
  }
}

double stable_step(const Hydro& s, int* limiting) {
  const Particles& P = s.particles;
  double best = std::numeric_limits<double>::infinity();
  int where = -1;
  for (int i = 0; i < P.size(); ++i) {
    const double speed = std::sqrt(P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] +
                                   P.v[3 * i + 2] * P.v[3 * i + 2]);
    const double dt = P.h[i] / (P.c[i] + speed);
    if (dt < best) best = dt, where = i;
  }
  if (limiting) *limiting = where;
  return s.settings.courant * best;
}

namespace {
void check_finite(const Hydro& s) {
  const Particles& P = s.particles;
  for (int i = 0; i < P.size(); ++i)
    if (!std::isfinite(P.rho[i]) || !std::isfinite(P.e[i]) || !(P.rho[i] > 0.0) ||
        !std::isfinite(P.v[3 * i]) || !std::isfinite(P.v[3 * i + 1]) ||
        !std::isfinite(P.v[3 * i + 2]))
      fail("SPH: particle ", i, " at (", P.x[3 * i], ", ", P.x[3 * i + 1], ", ", P.x[3 * i + 2],
           ") has density ", P.rho[i], ", energy ", P.e[i], ", velocity (", P.v[3 * i], ", ",
           P.v[3 * i + 1], ", ", P.v[3 * i + 2], ") at step ", s.step, ", t = ", s.time);
}
} // namespace

void advance(Hydro& s, double dt) {
  Particles& P = s.particles;
  const int n = P.size();
  const std::size_t n3 = 3 * static_cast<std::size_t>(n);
  const std::vector<double> x0 = P.x, v0 = P.v, rho0 = P.rho, e0 = P.e;
  const double t0 = s.time;
  Rates r;
  // Predictor: half a step with the rates at the start.
  refresh_neighbours(s);
  compute_rates(s, r);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.x[k] = x0[k] + 0.5 * dt * v0[k];
    P.v[k] = v0[k] + 0.5 * dt * r.dv[k];
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.rho[i] = rho0[i] + 0.5 * dt * r.drho[i];
    P.e[i] = e0[i] + 0.5 * dt * r.de[i];
  }
  s.time = t0 + 0.5 * dt;
  update_state(s);
  // Corrector: the full step with the mid-step rates.
  refresh_neighbours(s);
  compute_rates(s, r);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.x[k] = x0[k] + dt * P.v[k];
    P.v[k] = v0[k] + dt * r.dv[k];
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.rho[i] = rho0[i] + dt * r.drho[i];
    P.e[i] = e0[i] + dt * r.de[i];
  }
  s.time = t0 + dt;
  ++s.step;
  check_finite(s);
  update_state(s);
}

Energies energies(const Hydro& s) {
  const Particles& P = s.particles;
  Energies out;
  for (int i = 0; i < P.size(); ++i) {
    const double v2 =
        P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] + P.v[3 * i + 2] * P.v[3 * i + 2];
    out.kinetic += 0.5 * P.mass[i] * v2;
    out.internal += P.mass[i] * P.e[i];
  }
  return out;
}

} // namespace mf::sph
