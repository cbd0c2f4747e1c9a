#include "meshfree/sph/step.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
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
  // The rank that holds the smallest step names its particle; the others name none.
  if (!s.ranks.serial()) {
    if (s.ranks.rank_of_min(best) != s.ranks.rank) where = -1;
    best = s.ranks.min(best);
  }
  if (limiting) *limiting = where;
  return s.settings.courant * best;
}

namespace {
/// Fails, naming the particle, when a particle's density is not positive or its energy or
/// velocity not finite (`stage`: which state of the step is checked). Collective.
void check_finite(const Hydro& s, const char* stage) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  int bad = -1;
  for (const int i : P.all())
    if (!std::isfinite(F.rho[i]) || !std::isfinite(F.e[i]) || !(F.rho[i] > 0.0) ||
        !std::isfinite(P.v[3 * i]) || !std::isfinite(P.v[3 * i + 1]) ||
        !std::isfinite(P.v[3 * i + 2])) {
      bad = i;
      break;
    }
  // On more than one rank, every rank fails with the report of the lowest rank that found one:
  // id, position, density, energy, velocity, and 1 for found.
  double report[10] = {};
  if (bad >= 0) {
    const Vec3 x = P.position(bad);
    report[0] = static_cast<double>(P.id[bad]);
    for (int d = 0; d < 3; ++d) report[1 + d] = x[d], report[6 + d] = P.v[3 * bad + d];
    report[4] = F.rho[bad], report[5] = F.e[bad], report[9] = 1.0;
  }
  if (!s.ranks.serial()) {
    const int holder = s.ranks.rank_of_min(bad >= 0 ? static_cast<double>(s.ranks.rank) : 1e300);
    s.ranks.broadcast(report, 10, holder);
  }
  if (report[9] == 0.0) return;
  fail("SPH: particle ", static_cast<long>(report[0]), " at (", report[1], ", ", report[2], ", ",
       report[3], ") has density ", report[4], ", energy ", report[5], ", velocity (", report[6],
       ", ", report[7], ", ", report[8], ") ", stage, " of step ", s.particles.step + 1,
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
  const double c = std::max(s.body.damping, 0.0);
  double gravity = 0.0, damping = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : gravity, damping)
  for (int i = 0; i < n; ++i) {
    if (F.fixed[i]) continue;
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      const double mean_v = v0[k] + 0.5 * dt * dv[k];
      gravity += P.mass[i] * s.body.gravity[d] * mean_v;
      damping -= c * P.mass[i] * P.v[k] * mean_v;
    }
  }
  s.external_work += dt * (gravity + damping);
  s.damping_work += dt * damping;
}

/// rho = rho0 + dt drho held within [rho_lo, rho_hi], and e = e0 + dt de, for the owned
/// particles; returns those held. Without the bound a particle whose neighbours recede loses
/// density at a rate that does not fall with it, through zero, once its h no longer grows to take
/// in more of them (the first particle of the light gas in Sod's tube, within 20 steps); with it,
/// its volume and h stop at the bound, as AUTODYN's density limits hold an SPH particle's.
SmoothingBoundHits update_density_energy(Hydro& s, const std::vector<double>& rho0,
                                         const std::vector<double>& e0, const Rates& r, double dt) {
  ParticleFields& F = s.fields;
  long at_min = 0, at_max = 0;
  const int n = s.particles.owned_count();
#pragma omp parallel for schedule(static) reduction(+ : at_min, at_max)
  for (int i = 0; i < n; ++i) {
    const double rho = rho0[i] + dt * r.drho[i];
    // min(max()), not std::clamp: defined for whatever bounds a checkpoint gave back.
    F.rho[i] = std::min(std::max(rho, F.rho_lo[i]), F.rho_hi[i]);
    F.e[i] = e0[i] + dt * r.de[i];
    if (rho < F.rho_lo[i]) ++at_max;
    if (rho > F.rho_hi[i]) ++at_min;
  }
  return {at_min, at_max};
}

} // namespace

void advance(Hydro& s, double dt) {
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  // A build at the start of the step may move particles to other ranks: before anything is kept.
  refresh_neighbours(s, true);
  const int n = P.owned_count(); // ghosts are refreshed from these after each stage
  const std::size_t n3 = 3 * static_cast<std::size_t>(n);
  const std::vector<double> u0 = P.u, v0 = P.v, rho0 = F.rho, e0 = F.e;
  const StressHistory start = stress_history(s);
  const bool solids = s.any_solid();
  const double t0 = s.particles.time;
  Rates r;
  // Predictor: half a step with the rates at the start.
  compute_rates(s, r);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.u[k] = u0[k] + 0.5 * dt * v0[k];
    P.v[k] = v0[k] + 0.5 * dt * r.dv[k];
  }
  update_density_energy(s, rho0, e0, r, 0.5 * dt);
  if (solids) update_stress(s, start, r, 0.5 * dt);
  s.particles.time = t0 + 0.5 * dt;
  // A density that is not positive at the half step would give its neighbours a non-finite h
  // (h follows rho^(-1/dim)): the failure names this particle, not theirs.
  check_finite(s, "at the half step");
  refresh_ghosts(s);
  update_state(s);
  // The loads' forces at the midpoint, which the corrector applies over the whole step.
  std::vector<int> loaded;
  std::vector<double> mid_force;
  external_forces(s, loaded, mid_force);
  // Corrector: the full step with the mid-step rates.
  refresh_neighbours(s);
  compute_rates(s, r);
  if (s.body.any()) body_force_work(s, v0, r.dv, dt);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.u[k] = u0[k] + dt * P.v[k];
    P.v[k] = v0[k] + dt * r.dv[k];
  }
  const SmoothingBoundHits held = update_density_energy(s, rho0, e0, r, dt);
  if (solids) update_stress(s, start, r, dt);
  // Their work: F_mid . (v0 + v1) / 2 dt, which is exactly the kinetic energy the corrector's
  // velocity update gives them, pulses that arrive within the step included.
  for (std::size_t k = 0; k < loaded.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const std::size_t at = 3 * static_cast<std::size_t>(loaded[k]) + d;
      s.external_work += dt * mid_force[3 * k + d] * 0.5 * (v0[at] + P.v[at]);
    }
  s.particles.time = t0 + dt;
  check_finite(s, "at the end");
  ++s.particles.step;
  s.bounded_h += held;
  commit_history(s);
  refresh_ghosts(s);
  update_state(s);
}

Energies energies(const Hydro& s) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  // Summed in extended precision: a sum of 10^5 terms of one sign in doubles carries round-off
  // of about 1e-12 that depends on the order, which would make a run spread over ranks (each
  // rank's part summed first) differ from one rank by more than its fields do.
  long double kinetic = 0.0L, internal = 0.0L;
  for (const int i : P.owned()) {
    const double v2 =
        P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] + P.v[3 * i + 2] * P.v[3 * i + 2];
    kinetic += 0.5 * P.mass[i] * v2;
    internal += P.mass[i] * F.e[i];
  }
  double sums[2] = {static_cast<double>(kinetic), static_cast<double>(internal)};
  s.ranks.sum(sums, 2);
  return {sums[0], sums[1]};
}

} // namespace mf::sph
