// The SPH stage of a staged run (stages/explicit_stage.hpp).
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/run_summaries.hpp"
#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/held_loads.hpp"
#include "meshfree/sph/initial_state.hpp"
#include "meshfree/sph/step.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include "meshfree/stages/held_conditions.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>

namespace mf::stages {

namespace {

std::vector<materials::Vec6> back_stresses(const PreloadAtParticles& pa) {
  std::vector<materials::Vec6> b;
  for (const auto& h : pa.history) b.push_back(h.back_stress);
  return b;
}

/// The particle's state at increment k of the preload (the last: with its plastic history).
sph::InitialStateReport put_increment(sph::Hydro& h, const PreloadAtParticles& pa, int k,
                                      bool return_to_surface) {
  sph::set_displacement(h, flat(pa.u[k]));
  const bool last = k + 1 == pa.increments();
  return sph::set_initial_state(h, pa.stress[k], pa.alpha[k],
                                last ? back_stresses(pa) : std::vector<materials::Vec6>{},
                                return_to_surface);
}

/// The transmitting boundary of the stage most of whose particles a held condition acts on, or
/// -1: a roller or clamp there becomes the dashpot with its static force.
int transmitting_of(const sph::Hydro& h, const std::vector<int>& particles) {
  for (std::size_t b = 0; b < h.transmitting.size(); ++b) {
    const auto& p = h.transmitting[b].particles;
    std::size_t shared = 0;
    for (int i : particles) shared += std::binary_search(p.begin(), p.end(), i);
    if (2 * shared > particles.size()) return static_cast<int>(b);
  }
  return -1;
}

struct Holding {
  std::vector<std::string> how;
  std::vector<int> held_boundaries;           // transmitting boundaries holding their stress
};

/// A held force acts on the surface layer, one (smallest) particle spacing deep; a held
/// displacement holds the particles within the kernel's reach (r < h_i + h_j) of its boundary.
HoldLayers hold_layers(const io::SphSpec& s, const sph::Hydro& h) {
  HoldLayers l;
  l.surface = s.regions.front().spacing;
  for (const auto& r : s.regions) l.surface = std::min(l.surface, r.spacing);
  for (int i = 0; i < h.particles.owned_count(); ++i) l.held = std::max(l.held, 2.0 * h.fields.h[i]);
  return l;
}

/// A held displacement on the SPH body, and how it is held: a transmitting boundary of the stage
/// on the same particles keeps its dashpots with the static force of the preload's stress; a
/// roller at zero on a straight edge along an axis is a symmetry plane (mirror particles give
/// every particle its whole neighbourhood); otherwise the condition's layer, the kernel's reach
/// deep, keeps the preload's displacement: fixed particles for a clamp, the held component for a
/// roller.
std::string hold_displacement(const HeldCondition& c, sph::Hydro& h,
                              std::vector<int>& held_boundaries) {
  const int b = transmitting_of(h, c.surface);
  if (b >= 0) {
    held_boundaries.push_back(b);
    return detail::concat(c.name, ": transmitting boundary '", h.transmitting[b].name,
                          "' with the static force of the preload's stress");
  }
  if (c.kind == HeldCondition::Kind::Clamp) {
    for (int i : c.particles) h.fields.fixed[i] = 1;
    return detail::concat(c.name, ": ", c.particles.size(),
                          " fixed particles (the kernel's reach deep) at the preload's "
                          "displacement");
  }
  if (c.on_axis_line && c.value == 0.0) {
    h.symmetry.push_back({c.component, c.line});
    return detail::concat(c.name, ": symmetry plane ", "xyz"[c.component], " = ", c.line);
  }
  for (int i : c.particles) h.fields.held_axes[i] |= static_cast<char>(1 << c.component);
  return detail::concat(c.name, ": ", "xyz"[c.component], " component of ", c.particles.size(),
                        " particles (the kernel's reach deep) held at the preload's displacement");
}

/// The held conditions on the SPH body: forces, fixed particles, symmetry planes, dashpots with
/// their static force, gravity.
Holding hold(const std::vector<HeldCondition>& held, const io::ProblemSpec& preload,
             const io::StageLink& link, sph::Hydro& h) {
  Holding out;
  for (const HeldCondition& c : held) {
    switch (c.kind) {
    case HeldCondition::Kind::Force: {
      sph::SurfaceForce f;
      f.name = c.name;
      f.particles = c.particles;
      Vec3 total = Vec3::Zero();
      for (const Vec3& F : c.force) {
        f.force.insert(f.force.end(), {F.x(), F.y(), F.z()});
        total += F;
      }
      h.forces.push_back(f);
      out.how.push_back(detail::concat(c.name, ": constant force on ", c.particles.size(),
                                       " particles, total (", total.x(), ", ", total.y(), ")"));
      break;
    }
    case HeldCondition::Kind::Body: {
      MF_REQUIRE(c.gravity, link.key_path, ".hold: '", c.name,
                 "': SPH holds gravity, not a "
                 "uniform body force (give the preload 'gravity')");
      for (int d = 0; d < 2; ++d) h.gravity[d] = c.body_factor * preload.gravity[d];
      out.how.push_back(detail::concat(c.name, ": gravity (", h.gravity[0], ", ", h.gravity[1],
                                       ") on every particle"));
      break;
    }
    case HeldCondition::Kind::Clamp:
    case HeldCondition::Kind::Roller:
      out.how.push_back(hold_displacement(c, h, out.held_boundaries));
      break;
    }
  }
  return out;
}

/// The scale of the out-of-balance forces: the largest held force on a particle, or the largest
/// stress component times a particle's face area.
double largest_force(const sph::Hydro& h, const std::vector<materials::Vec6>& sigma) {
  double f = 0.0;
  const particles::ParticleSet& P = h.particles;
  for (std::size_t i = 0; i < sigma.size(); ++i)
    f = std::max(f, sigma[i].cwiseAbs().maxCoeff() * sph::face_area(P, static_cast<int>(i), h.dim));
  for (const auto& s : h.forces)
    for (std::size_t k = 0; k < s.particles.size(); ++k)
      f = std::max(f, Vec3(s.force[3 * k], s.force[3 * k + 1], s.force[3 * k + 2]).norm());
  for (const auto& b : h.transmitting)
    for (std::size_t k = 0; k < b.static_force.size() / 3; ++k)
      f = std::max(
          f,
          Vec3(b.static_force[3 * k], b.static_force[3 * k + 1], b.static_force[3 * k + 2]).norm());
  const double g = Vec3(h.gravity[0], h.gravity[1], h.gravity[2]).norm();
  for (int i = 0; i < P.owned_count(); ++i) f = std::max(f, P.mass[i] * g);
  return f;
}

/// The largest out-of-balance force of a free particle at the current state held at rest.
double worst_out_of_balance(sph::Hydro& h) {
  const std::vector<double> ob = sph::out_of_balance(h);
  double worst = 0.0;
  for (int i = 0; i < h.particles.owned_count(); ++i)
    worst = std::max(worst, Vec3(ob[3 * i], ob[3 * i + 1], ob[3 * i + 2]).norm());
  return worst;
}

/// The particles whose out-of-balance the transfer balances: every particle, except those
/// within the kernel's reach of a released condition (a released body force: all of them), so
/// that a release still acts. What is balanced is what the SPH sums of the transferred stress
/// leave unbalanced where the Galerkin solution is in equilibrium: truncated kernels at free
/// surfaces that are not straight (a hole stepped by the lattice), stress gradients the
/// particles resolve differently, the plastic zone's kinks. Constant forces -m_i a_i hold that
/// state at rest without moving it: a settle (damped motion to the particles' own equilibrium)
/// would change the transferred stress instead (by 7% in a gripped homogeneous block).
std::vector<int> balanced_particles(const io::ProblemSpec& preload,
                                    const implicit::ElastoplasticResult& pre,
                                    const io::StageLink& link, const std::vector<Vec3>& X,
                                    const sph::Hydro& h, double reach) {
  const int n = h.particles.owned_count();
  std::vector<char> released(n, 0);
  io::StageLink off = link;
  off.hold = link.release;
  for (const HeldCondition& c : held_conditions(preload, pre, off, X, {reach, reach})) {
    if (c.kind == HeldCondition::Kind::Body) return {};
    for (int i : c.particles) released[i] = 1;
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (!released[i]) out.push_back(i);
  return out;
}

} // namespace

ExplicitStage run_sph_stage(const io::ProblemSpec& preload,
                            const implicit::ElastoplasticResult& pre, const io::ProblemSpec& stage,
                            const io::StageLink& link, int index, io::OutputDirectory* out,
                            const StageCheckpoints& checkpoints) {
  const io::SphSpec& s = *stage.sph;
  ExplicitStage st;
  explicit_dynamics::SphRunResult result;
  sph::Hydro h;
  {
    PhaseTimer::Scope scope(result.timer, "particles");
    h = explicit_dynamics::build_sph(s);
  }
  // `check` refuses an endless stage before anything runs; here it stops before the stage does.
  explicit_dynamics::require_finite_run(
      explicit_dynamics::planned_run(s, h.particles.size(), sph::stable_step(h)),
      out ? out->dir() : ".");
  const int n = h.particles.owned_count();
  TransferReport& t = st.transfer;
  PreloadAtParticles pa;
  {
    PhaseTimer::Scope scope(result.timer, "transfer");
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Vec3> X(n);
    for (int i = 0; i < n; ++i) X[i] = h.particles.reference(i);
    pa = sample_preload(preload, pre, X, link.mirror, link.key_path);
    const HoldLayers layers = hold_layers(s, h);
    const Holding held = hold(held_conditions(preload, pre, link, X, layers), preload, link, h);
    t.held = held.how;
    const sph::InitialStateReport rep =
        put_increment(h, pa, pa.increments() - 1, link.return_to_surface);
    std::vector<materials::Vec6> sigma(h.particles.size(), materials::Vec6::Zero());
    std::copy(pa.final_stress().begin(), pa.final_stress().end(), sigma.begin());
    // Every held boundary takes its static force before the balance is computed: a balance
    // taken while a boundary still lacks its static force would carry its share of the body's
    // weight and stress.
    for (int b : held.held_boundaries) sph::hold_stress(h.transmitting[b], sigma);
    const double scale = std::max(largest_force(h, pa.final_stress()), 1e-300);
    t.balanced_residual = worst_out_of_balance(h) / scale;
    h.forces.push_back(sph::balancing_force(
        h, "transfer_balance", balanced_particles(preload, pre, link, X, h, layers.held)));
    t.out_of_balance = worst_out_of_balance(h) / scale;
    t.particles = n;
    t.over_surface = rep.over_surface;
    t.returned = rep.returned;
    t.worst_yield_ratio = rep.worst_ratio;
    t.density_mismatch = rep.density_mismatch;
    for (int i = 0; i < n; ++i) {
      t.plastic_particles += pa.plastic[i];
      t.max_u = std::max(t.max_u, pa.final_u()[i].norm());
    }
    t.stored_energy = stored_energy(preload, pa, h.particles.volume);
    t.seconds = seconds_since(t0);
  }
  if (link.settle_time > 0.0) {
    PhaseTimer::Scope scope(result.timer, "settle");
    const std::vector<double> u0 = h.particles.u;
    // The settle is the preload's, under the held loads alone: the event's own pressure
    // histories (a blast) start at t = 0, after it.
    std::vector<sph::SurfaceLoad> event_loads;
    std::swap(event_loads, h.loads);
    h.damping = link.settle_damping;
    const auto began = std::chrono::steady_clock::now();
    double next_report = 0.1, last_report = 0.0;
    while (h.particles.time < link.settle_time) {
      sph::advance(h, std::min(sph::stable_step(h), link.settle_time - h.particles.time));
      // Every tenth of the settle, or every 10 s of wall time, and at its end.
      const double done = h.particles.time / link.settle_time, wall = seconds_since(began);
      if (done >= next_report || wall >= last_report + 10.0 || done >= 1.0) {
        log::info("  settle: t = ", h.particles.time, " (", std::lround(100.0 * done),
                  "%), step ", h.particles.step, ", ", log::eta(wall, done));
        while (next_report <= done) next_report += 0.1;
        last_report = wall;
      }
    }
    std::swap(event_loads, h.loads);
    double drift = 0.0;
    for (int i = 0; i < n; ++i)
      drift = std::max(drift, Vec3(h.particles.u[3 * i] - u0[3 * i],
                                   h.particles.u[3 * i + 1] - u0[3 * i + 1],
                                   h.particles.u[3 * i + 2] - u0[3 * i + 2])
                                  .norm());
    t.settle_time = link.settle_time;
    t.settle_drift = drift / std::max(t.max_u, 1e-300);
    h.damping = 0.0;
    sph::set_displacement(
        h, std::vector<double>(h.particles.u.begin(), h.particles.u.begin() + 3 * n));
    h.particles.time = 0.0;
    h.particles.step = 0;
    h.external_work = h.damping_work = 0.0;
  }
  log::info("transfer: ", n, " particles from stage ", preload.stage, ", ", t.plastic_particles,
            " plastic, ", t.over_surface, " over their yield surface (worst q/Y ",
            t.worst_yield_ratio, "), residual of the SPH sums ", t.balanced_residual,
            " balanced, out-of-balance ", t.out_of_balance,
            link.settle_time > 0.0 ? detail::concat(", settle drift ", t.settle_drift) : "");

  // Over several ranks, each keeps its slab of the body with its share of the held forces and
  // balance (sph::distribute), and the preload at its own particles.
  if (!checkpoints.ranks.serial()) {
    PhaseTimer::Scope scope(result.timer, "split over ranks");
    sph::distribute(h, checkpoints.ranks);
    pa = select_particles(pa, std::vector<long>(h.particles.id.begin(),
                                                h.particles.id.begin() + h.particles.owned_count()));
    log::info("sph: spread over ", checkpoints.ranks.size, " MPI ranks");
  }
  explicit_dynamics::SphRun run(h, s, out, result);
  run.set_energy_scale(t.stored_energy);
  // The preload replayed on the particles, then the transferred state back for t = 0.
  const sph::Hydro start = h;
  // The last increment is recorded (at t = 0, as the preload's end) but not written as a field
  // step: the run's first step is the same instant.
  const int N = pa.increments() - 1;
  for (int k = 0; k <= N; ++k) {
    put_increment(h, pa, k, false);
    h.particles.time = pa.pseudo_time[k];
    run.record();
    if (k < N) run.write_fields();
  }
  h = start;
  const io::History replay = take_rows(result.history);
  begin_stage_history(st, replay, result.history, s.gauges, link.from, index, out);
  result.energy_error = 0.0;
  run.finish(explicit_dynamics::run_time_loop(run,
                                              {s.end_time, s.history_interval, s.fields_interval},
                                              checkpoints.checkpoints, checkpoints.resume));

  explicit_dynamics::summarise(result, st.counts, st.time_step, st.results);
  record_stage(st, result.status, result.stop_reason, result.timer);
  st.plastic_strain.assign(h.fields.alpha.begin(), h.fields.alpha.begin() + n);
  for (int i = 0; i < n; ++i) {
    materials::Vec6 sigma;
    for (int k = 0; k < 6; ++k) sigma[k] = h.fields.S[6 * i + k] - (k < 3 ? h.fields.p[i] : 0.0);
    st.stress.push_back(sigma);
  }
  st.displacement.assign(h.particles.u.begin(), h.particles.u.begin() + 3 * n);
  st.position.assign(h.particles.X.begin(), h.particles.X.begin() + 3 * n);
  return st;
}

} // namespace mf::stages
