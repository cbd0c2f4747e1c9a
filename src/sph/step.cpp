#include "meshfree/sph/step.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace mf::sph {

double stable_step(const Hydro& s, int* limiting) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  double best = std::numeric_limits<double>::infinity();
  int where = -1;
  for (const int i : P.owned()) {
    const double speed = std::sqrt(P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] +
                                   P.v[3 * i + 2] * P.v[3 * i + 2]);
    const double dt = F.h[i] / (F.c[i] + speed);
    if (dt < best) best = dt, where = i;
  }
  if (limiting) *limiting = where;
  return s.settings.courant * best;
}

namespace {
void check_finite(const Hydro& s) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  for (const int i : P.all())
    if (!std::isfinite(F.rho[i]) || !std::isfinite(F.e[i]) || !(F.rho[i] > 0.0) ||
        !std::isfinite(P.v[3 * i]) || !std::isfinite(P.v[3 * i + 1]) ||
        !std::isfinite(P.v[3 * i + 2]))
      fail("SPH: particle ", i, " at (", P.position(i).x(), ", ", P.position(i).y(), ", ",
           P.position(i).z(), ") has density ", F.rho[i], ", energy ", F.e[i], ", velocity (",
           P.v[3 * i], ", ", P.v[3 * i + 1], ", ", P.v[3 * i + 2], ") at step ", s.particles.step,
           ", t = ", s.particles.time);
}
/// The work of gravity and damping over a step whose corrector applies the mid-step velocities
/// P.v and the accelerations dv: m (g - c v_mid) . (v0 + v1) / 2 dt, v1 = v0 + dt dv, which is
/// exactly the kinetic energy these forces give in the corrector's velocity update.
void body_force_work(Hydro& s, const std::vector<double>& v0, const std::vector<double>& dv,
                     double dt) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const int n = P.owned_count();
  const double c = std::max(s.damping, 0.0);
  double gravity = 0.0, damping = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : gravity, damping)
  for (int i = 0; i < n; ++i) {
    if (F.fixed[i]) continue;
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      const double mean_v = v0[k] + 0.5 * dt * dv[k];
      gravity += P.mass[i] * s.gravity[d] * mean_v;
      damping -= c * P.mass[i] * P.v[k] * mean_v;
    }
  }
  s.external_work += dt * (gravity + damping);
  s.damping_work += dt * damping;
}

} // namespace

void advance(Hydro& s, double dt) {
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  const int n = P.owned_count(); // ghosts are mirrored from these after each stage
  const std::size_t n3 = 3 * static_cast<std::size_t>(n);
  const std::vector<double> u0 = P.u, v0 = P.v, rho0 = F.rho, e0 = F.e;
  const StressHistory start = stress_history(s);
  const bool solids = s.any_solid();
  const double t0 = s.particles.time;
  Rates r;
  // Predictor: half a step with the rates at the start.
  refresh_neighbours(s);
  compute_rates(s, r);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.u[k] = u0[k] + 0.5 * dt * v0[k];
    P.v[k] = v0[k] + 0.5 * dt * r.dv[k];
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    F.rho[i] = rho0[i] + 0.5 * dt * r.drho[i];
    F.e[i] = e0[i] + 0.5 * dt * r.de[i];
  }
  if (solids) update_stress(s, start, r, 0.5 * dt);
  s.particles.time = t0 + 0.5 * dt;
  refresh_ghosts(s);
  update_state(s);
  // The loads' forces at the midpoint, which the corrector applies over the whole step.
  std::vector<int> loaded;
  std::vector<double> mid_force;
  external_forces(s, loaded, mid_force);
  // Corrector: the full step with the mid-step rates.
  refresh_neighbours(s);
  compute_rates(s, r);
  if (s.gravity[0] != 0.0 || s.gravity[1] != 0.0 || s.gravity[2] != 0.0 || s.damping > 0.0)
    body_force_work(s, v0, r.dv, dt);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.u[k] = u0[k] + dt * P.v[k];
    P.v[k] = v0[k] + dt * r.dv[k];
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    F.rho[i] = rho0[i] + dt * r.drho[i];
    F.e[i] = e0[i] + dt * r.de[i];
  }
  if (solids) update_stress(s, start, r, dt);
  // Their work: F_mid . (v0 + v1) / 2 dt, which is exactly the kinetic energy the corrector's
  // velocity update gives them, pulses that arrive within the step included.
  for (std::size_t k = 0; k < loaded.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const std::size_t at = 3 * static_cast<std::size_t>(loaded[k]) + d;
      s.external_work += dt * mid_force[3 * k + d] * 0.5 * (v0[at] + P.v[at]);
    }
  s.particles.time = t0 + dt;
  ++s.particles.step;
  check_finite(s);
  commit_history(s);
  refresh_ghosts(s);
  update_state(s);
}

Energies energies(const Hydro& s) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  Energies out;
  for (const int i : P.owned()) {
    const double v2 =
        P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] + P.v[3 * i + 2] * P.v[3 * i + 2];
    out.kinetic += 0.5 * P.mass[i] * v2;
    out.internal += P.mass[i] * F.e[i];
  }
  return out;
}

} // namespace mf::sph
