// The SPH stage of a staged run (stages/explicit_stage.hpp).
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/initial_state.hpp"
#include "meshfree/sph/step.hpp"
#include "meshfree/sph/support_balance.hpp"
#include "meshfree/sph/surface_force.hpp"
#include "meshfree/sph/transmitting_boundary.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include "meshfree/stages/held_conditions.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include "meshfree/stages/stage_run.hpp"
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
int transmitting_of(sph::Hydro& h, const std::vector<int>& particles) {
  const std::vector<sph::TransmittingBoundary*> boundaries =
      h.conditions.of_kind<sph::TransmittingBoundary>();
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    const auto& p = boundaries[b]->particles;
    std::size_t shared = 0;
    for (int i : particles) shared += std::binary_search(p.begin(), p.end(), i);
    if (2 * shared > particles.size()) return static_cast<int>(b);
  }
  return -1;
}

struct Holding {
  std::vector<std::string> how;
  std::vector<int> held_boundaries; // transmitting boundaries holding their stress
};

/// A held force acts on the surface layer, one (smallest) particle spacing deep; a held
/// displacement holds the particles within the kernel's reach (r < h_i + h_j) of its boundary.
HoldLayers hold_layers(const spec::SphSpec& s, const sph::Hydro& h) {
  HoldLayers l;
  l.surface = s.regions.front().spacing;
  for (const auto& r : s.regions) l.surface = std::min(l.surface, r.spacing);
  for (int i = 0; i < h.particles.owned_count(); ++i)
    l.held = std::max(l.held, 2.0 * h.fields.h[i]);
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
    return detail::concat(c.name, ": transmitting boundary '",
                          h.conditions.of_kind<sph::TransmittingBoundary>()[b]->name,
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
Holding hold(const std::vector<HeldCondition>& held, const Preload& preload,
             const spec::StageLink& link, sph::Hydro& h) {
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
      h.conditions.add(std::move(f));
      out.how.push_back(detail::concat(c.name, ": constant force on ", c.particles.size(),
                                       " particles, total ", vector_text(total, preload)));
      break;
    }
    case HeldCondition::Kind::Body: {
      MF_REQUIRE(c.gravity, link.key_path, ".hold: '", c.name,
                 "': SPH holds gravity, not a "
                 "uniform body force (give the preload 'gravity')");
      const Vec3 g = c.body_factor * preload.gravity();
      for (int d = 0; d < 3; ++d) h.body.gravity[d] = g[d];
      out.how.push_back(
          detail::concat(c.name, ": gravity ", vector_text(g, preload), " on every particle"));
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

/// The particles whose out-of-balance the transfer balances (sph/support_balance.hpp): every
/// particle, except those within the kernel's reach of a released condition (a released body
/// force: all of them), so that a release still acts.
std::vector<int> balanced_particles(const Preload& preload, const spec::StageLink& link,
                                    const std::vector<Vec3>& X, const sph::Hydro& h, double reach) {
  const int n = h.particles.owned_count();
  std::vector<char> released(n, 0);
  spec::StageLink off = link;
  off.hold = link.release;
  for (const HeldCondition& c : preload.held(off, X, {reach, reach})) {
    if (c.kind == HeldCondition::Kind::Body) return {};
    for (int i : c.particles) released[i] = 1;
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (!released[i]) out.push_back(i);
  return out;
}

/// The stage's body from its own spec; `check` refuses an endless stage before anything runs,
/// and this stops it before it does.
sph::Hydro build_body(const spec::SphSpec& s, PhaseTimer& timer, const io::OutputDirectory* out) {
  sph::Hydro h;
  {
    PhaseTimer::Scope scope(timer, "particles");
    h = explicit_dynamics::build_sph(s);
  }
  explicit_dynamics::require_finite_run(explicit_dynamics::planned_run(s, h),
                                        out ? out->dir() : ".");
  return h;
}

/// The preload's final state on the whole body, held by its held conditions and balanced at rest
/// (sph::hold_at_rest); returns the preload at the particles.
PreloadAtParticles transfer(const Preload& preload, const spec::StageLink& link,
                            const spec::SphSpec& s, sph::Hydro& h, TransferReport& t) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Vec3> X = reference_positions(h.particles, h.particles.owned_count());
  PreloadAtParticles pa = preload.sample(X, link);
  const HoldLayers layers = hold_layers(s, h);
  const Holding held = hold(preload.held(link, X, layers), preload, link, h);
  t.held = held.how;
  const sph::InitialStateReport rep =
      put_increment(h, pa, pa.increments() - 1, link.return_to_surface);
  const sph::RestBalance balance =
      sph::hold_at_rest(h, pa.final_stress(), held.held_boundaries,
                        balanced_particles(preload, link, X, h, layers.held));
  t.balanced_residual = balance.before;
  t.out_of_balance = balance.after;
  t.over_surface = rep.over_surface;
  t.returned = rep.returned;
  t.worst_yield_ratio = rep.worst_ratio;
  t.density_mismatch = rep.density_mismatch;
  describe_preload(t, preload, pa, h.particles.volume);
  t.seconds = seconds_since(t0);
  return pa;
}

/// Damped motion under the held loads alone for link.settle_time, with a progress line every
/// tenth of it, or every 10 s of wall time, and at its end.
void damped_motion(sph::Hydro& h, const spec::StageLink& link) {
  const auto began = std::chrono::steady_clock::now();
  double next_report = 0.1, last_report = 0.0;
  while (h.particles.time < link.settle_time) {
    sph::advance(h, std::min(sph::stable_step(h), link.settle_time - h.particles.time));
    const double done = h.particles.time / link.settle_time, wall = seconds_since(began);
    if (done >= next_report || wall >= last_report + 10.0 || done >= 1.0) {
      log::info("  settle: t = ", h.particles.time, " (", std::lround(100.0 * done), "%), step ",
                h.particles.step, ", ", log::eta(wall, done));
      while (next_report <= done) next_report += 0.1;
      last_report = wall;
    }
  }
}

/// The settle: the body's damped motion to its own equilibrium under the held loads, which then
/// starts the run at t = 0 at rest; the report gets how far it drifted from the preload.
void settle(sph::Hydro& h, const spec::StageLink& link, TransferReport& t) {
  const int n = h.particles.owned_count();
  const std::vector<double> u0 = h.particles.u;
  // The settle is the preload's, under the held loads alone: the event's own pressure
  // histories (a blast) start at t = 0, after it.
  sph::Conditions event_loads = h.conditions.take_event_loads();
  h.body.damping = link.settle_damping;
  damped_motion(h, link);
  h.conditions.add_all(std::move(event_loads));
  double drift = 0.0;
  for (int i = 0; i < n; ++i)
    drift = std::max(drift, Vec3(h.particles.u[3 * i] - u0[3 * i],
                                 h.particles.u[3 * i + 1] - u0[3 * i + 1],
                                 h.particles.u[3 * i + 2] - u0[3 * i + 2])
                                .norm());
  t.settle_time = link.settle_time;
  t.settle_drift = drift / std::max(t.max_u, 1e-300);
  h.body.damping = 0.0;
  sph::set_displacement(h,
                        std::vector<double>(h.particles.u.begin(), h.particles.u.begin() + 3 * n));
  h.particles.time = 0.0;
  h.particles.step = 0;
  h.external_work = h.damping_work = 0.0;
}

void log_transfer(const Preload& preload, const spec::StageLink& link, const TransferReport& t) {
  log::info("transfer: ", t.particles, " particles from stage ", preload.spec().stage, ", ",
            t.plastic_particles, " plastic, ", t.over_surface,
            " over their yield surface (worst q/Y ", t.worst_yield_ratio,
            "), residual of the SPH sums ", t.balanced_residual, " balanced, out-of-balance ",
            t.out_of_balance,
            link.settle_time > 0.0 ? detail::concat(", settle drift ", t.settle_drift) : "");
}

/// Over several ranks, each keeps its slab of the body with its share of the held forces and
/// balance (sph::distribute), and the preload at its own particles.
void spread_over_ranks(sph::Hydro& h, PreloadAtParticles& pa, const distribution::Ranks& ranks,
                       PhaseTimer& timer) {
  PhaseTimer::Scope scope(timer, "split over ranks");
  sph::distribute(h, ranks);
  pa = select_particles(pa, std::vector<long>(h.particles.id.begin(),
                                              h.particles.id.begin() + h.particles.owned_count()));
  log::info("sph: spread over ", ranks.size, " MPI ranks");
}

/// The owned particles' state at the end of the stage: plastic strain, Cauchy stress
/// (S - p I), displacement and reference position.
void keep_end_state(ExplicitStage& st, const sph::Hydro& h) {
  const int n = h.particles.owned_count();
  st.plastic_strain.assign(h.fields.alpha.begin(), h.fields.alpha.begin() + n);
  for (int i = 0; i < n; ++i) {
    materials::Vec6 sigma;
    for (int k = 0; k < 6; ++k) sigma[k] = h.fields.S[6 * i + k] - (k < 3 ? h.fields.p[i] : 0.0);
    st.stress.push_back(sigma);
  }
  st.displacement.assign(h.particles.u.begin(), h.particles.u.begin() + 3 * n);
  st.position.assign(h.particles.X.begin(), h.particles.X.begin() + 3 * n);
}

} // namespace

ExplicitStage run_sph_stage(const Preload& preload, const spec::ProblemSpec& stage,
                            const spec::StageLink& link, int index,
                            const explicit_dynamics::RunPlace& place) {
  const spec::SphSpec& s = stage.sph();
  ExplicitStage st;
  explicit_dynamics::SphRunResult result;
  sph::Hydro h = build_body(s, result.timer, place.out);
  PreloadAtParticles pa;
  {
    PhaseTimer::Scope scope(result.timer, "transfer");
    pa = transfer(preload, link, s, h, st.transfer);
  }
  if (link.settle_time > 0.0) {
    PhaseTimer::Scope scope(result.timer, "settle");
    settle(h, link, st.transfer);
  }
  log_transfer(preload, link, st.transfer);
  if (!place.ranks.serial()) spread_over_ranks(h, pa, place.ranks, result.timer);
  explicit_dynamics::SphRun run(h, s, place.out, result);
  run.set_energy_scale(st.transfer.stored_energy);
  const sph::Hydro start = h; // the transferred state, back for t = 0 after the replay
  replay_preload(run, pa.increments(), [&](int k) {
    put_increment(h, pa, k, false);
    h.particles.time = pa.pseudo_time[k];
  });
  run_stage(st, run, result, s, link, index, place, [&] {
    h = start;
    result.energy_error = 0.0;
  });
  keep_end_state(st, h);
  return st;
}

} // namespace mf::stages
