// Static equilibrium by relaxation (pd/relaxation.hpp): adaptive dynamic relaxation with its
// fictitious density, explicit dynamic relaxation with the physical one.
#include "meshfree/pd/relaxation.hpp"
#include "meshfree/core/error.hpp"
#include "static_loading.hpp"
#include <algorithm>
#include <cmath>

namespace mf::pd {

using namespace detail;

namespace {

/// Fictitious density of every component for a unit step (Kilic & Madenci 2010):
/// lambda_ii >= (1/4) dt^2 sum_j |K_ij| (Gershgorin's bound on the spectrum of D^-1 K, which
/// keeps the central difference stable). The stiffness of the linearised bond force is the
/// block K_ij = c w_ij / |xi_ij| e e^T (j != i) and K_ii = -sum_j K_ij, so that the row sum of
/// component d is at most 2 sum_j c w_ij / |xi_ij| |e_d| (|e_x| + |e_y| + |e_z|), over the
/// intact bonds at the reference directions e.
std::vector<double> fictitious_density(const Model& m, const BondState& s) {
  if (m.state_based()) return state_fictitious_density(m, s);
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  std::vector<double> lambda(3 * static_cast<std::size_t>(n), 0.0);
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const double L = c.length;
    const double e[3] = {(q.X[3 * j] - q.X[3 * i]) / L, (q.X[3 * j + 1] - q.X[3 * i + 1]) / L,
                         (q.X[3 * j + 2] - q.X[3 * i + 2]) / L};
    const double stiffness = m.laws[c.law].c * w / L;
    const double row = std::abs(e[0]) + std::abs(e[1]) + std::abs(e[2]);
    for (int d = 0; d < 3; ++d) lambda[3 * i + d] += 0.5 * stiffness * std::abs(e[d]) * row;
  });
  return lambda;
}

} // namespace

RelaxReport relax(Model& m, BondState& s, const Loading& loading, const RelaxSettings& settings) {
  const Clock::time_point start = Clock::now();
  NoBreaking guard(m, s, !settings.allow_breaking);
  particles::ParticleSet& q = m.particles;
  const std::size_t size = q.u.size();
  const Statics st = statics(m, loading);
  for (std::size_t k = 0; k < size; ++k)
    if (st.held[k]) q.u[k] = st.target[k];
  const std::vector<double> lambda = fictitious_density(m, s);
  // Components that move: free, with a stiffness to divide by.
  std::vector<unsigned char> moves(size);
  for (std::size_t k = 0; k < size; ++k) moves[k] = !st.held[k] && lambda[k] > 0.0;
  std::vector<double> y, f, f_old, v(size, 0.0);
  Norms norms = net_force(m, s, st, 1.0, y, f);
  RelaxReport r;
  r.residual_ratio = norms.ratio();
  while (!(r.residual_ratio <= settings.tolerance) && std::isfinite(r.residual_ratio) &&
         r.iterations < settings.max_iterations) {
    double c = 0.0;
    if (r.iterations > 0) {
      // Damping from the lowest frequency as a Rayleigh quotient (Kilic & Madenci 2010):
      // c^n = 2 sqrt((u^T K^n u) / (u^T u)) with the local diagonal stiffness
      // K_ii^n = -(F_i^n - F_i^n-1) / (lambda_ii dt v_i^n-1/2), dt = 1; no damping when the
      // quotient is not positive, and kept below 2, where the velocity factor (2 - c) / (2 + c)
      // of the update would change sign.
      double uKu = 0.0, uu = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : uKu, uu)
      for (std::size_t k = 0; k < size; ++k) {
        if (!moves[k]) continue;
        uu += q.u[k] * q.u[k];
        if (v[k] != 0.0) uKu -= q.u[k] * q.u[k] * (f[k] - f_old[k]) / (lambda[k] * v[k]);
      }
      if (uu > 0.0 && uKu > 0.0) c = std::min(2.0 * std::sqrt(uKu / uu), 1.9);
    }
    // Central-difference update with the fictitious density and damping (Kilic & Madenci 2010,
    // dt = 1): v^n+1/2 = ((2 - c^n) v^n-1/2 + 2 F^n / lambda) / (2 + c^n), started by
    // v^1/2 = F^0 / (2 lambda); u^n+1 = u^n + v^n+1/2.
    const bool first = r.iterations == 0;
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k) {
      if (!moves[k]) continue;
      v[k] =
          first ? 0.5 * f[k] / lambda[k] : ((2.0 - c) * v[k] + 2.0 * f[k] / lambda[k]) / (2.0 + c);
      q.u[k] += v[k];
    }
    ++r.iterations;
    f_old.swap(f);
    norms = net_force(m, s, st, 1.0, y, f);
    r.residual_ratio = norms.ratio();
  }
  r.converged = r.residual_ratio <= settings.tolerance;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
  r.seconds = seconds_since(start);
  return r;
}

ExplicitRelaxReport explicit_relax(Model& m, BondState& s, const Loading& loading,
                                   const ExplicitRelaxSettings& settings) {
  MF_REQUIRE(settings.dt > 0.0, "explicit relaxation: the time step must be positive");
  MF_REQUIRE(settings.ramp_time >= 0.0 && settings.damping >= 0.0,
             "explicit relaxation: the ramp time and the damping must not be negative");
  const Clock::time_point start = Clock::now();
  NoBreaking guard(m, s, !settings.allow_breaking);
  particles::ParticleSet& q = m.particles;
  const int n = q.size();
  const std::size_t size = q.u.size();
  const Statics st = statics(m, loading);
  const double dt = settings.dt, c = settings.damping;
  const auto ramp = [&](double t) {
    return settings.ramp_time > 0.0 ? std::min(t / settings.ramp_time, 1.0) : 1.0;
  };
  // Held components move from where they are to their targets along the ramp.
  const std::vector<double> u_start = q.u;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::vector<double> y, f;
  const auto accelerations = [&](double scale) {
    const Norms norms = net_force(m, s, st, scale, y, f);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) q.a[3 * i + d] = f[3 * i + d] / q.density[i];
    return norms;
  };
  double t = 0.0, scale = ramp(0.0);
  Norms norms = accelerations(scale);
  ExplicitRelaxReport r;
  while (r.steps < settings.max_steps) {
    // Velocity Verlet with a -= c v: the first half kick explicit in the damping, the second
    // implicit (v^n+1 = (v^n+1/2 + dt a^n+1 / 2) / (1 + c dt / 2)).
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k) {
      if (st.held[k]) continue;
      q.v[k] += 0.5 * dt * (q.a[k] - c * q.v[k]);
      q.u[k] += dt * q.v[k];
    }
    t += dt;
    scale = ramp(t);
    for (std::size_t k = 0; k < size; ++k)
      if (st.held[k]) {
        const double u =
            scale < 1.0 ? u_start[k] + scale * (st.target[k] - u_start[k]) : st.target[k];
        q.v[k] = (u - q.u[k]) / dt;
        q.u[k] = u;
      }
    norms = accelerations(scale);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k)
      if (!st.held[k]) q.v[k] = (q.v[k] + 0.5 * dt * q.a[k]) / (1.0 + 0.5 * c * dt);
    ++r.steps;
    const double kinetic = kinetic_energy(m);
    r.peak_kinetic = std::max(r.peak_kinetic, kinetic);
    r.kinetic_ratio = r.peak_kinetic > 0.0 ? kinetic / r.peak_kinetic : 0.0;
    // LS-DYNA's convergence test of dynamic relaxation: kinetic energy over its peak, once the
    // loads are fully on; or the residual ratio, when asked for.
    if (scale >= 1.0 && (kinetic <= settings.ke_ratio * r.peak_kinetic ||
                         norms.ratio() <= settings.residual_tolerance)) {
      r.converged = true;
      break;
    }
  }
  if (scale < 1.0) norms = net_force(m, s, st, 1.0, y, f);
  r.residual_ratio = norms.ratio();
  r.time = t;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
  r.seconds = seconds_since(start);
  return r;
}

void set_displacement(Model& m, const std::vector<double>& u) {
  particles::ParticleSet& q = m.particles;
  MF_REQUIRE(u.size() == q.u.size(), "peridynamics: a displacement needs 3 values per particle (",
             q.u.size(), "), got ", u.size());
  q.u = u;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
}

double residual_ratio(Model& m, BondState& s, const Loading& loading) {
  NoBreaking guard(m, s, true);
  const Statics st = statics(m, loading);
  std::vector<double> y, f;
  return net_force(m, s, st, 1.0, y, f).ratio();
}

} // namespace mf::pd
