// The SPH stage of a staged run (stages/explicit_stage.hpp).
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/run_summaries.hpp"
#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/implicit/point_law.hpp"
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
  std::vector<std::vector<int>> force_layers; // layers of held forces, to be balanced
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
      out.force_layers.push_back(c.particles);
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

/// Constant forces on the supporting particles that take the rigid-body part of the
/// out-of-balance of the rest of the body: -m_i (a + alpha e_z x (x_i - x_c)), a and alpha the
/// rigid translational and angular accelerations (about the supports' mass centre x_c, in the
/// plane) the rest's resultant F and moment M would give the supports, a = F / m, alpha = M / I,
/// I = sum m_i |x_i - x_c|^2. The supports then carry -F and -M and the body keeps only
/// self-equilibrated residuals (sph/held_loads.hpp, balancing_force).
sph::SurfaceForce rigid_balance(sph::Hydro& h, std::vector<int> support) {
  std::sort(support.begin(), support.end());
  support.erase(std::unique(support.begin(), support.end()), support.end());
  const particles::ParticleSet& P = h.particles;
  const std::vector<double> f = sph::out_of_balance(h);
  const auto x = [&P](int i, int d) { return P.X[3 * i + d] + P.u[3 * i + d]; };
  std::vector<char> in(P.owned_count(), 0);
  double m = 0.0, c[2] = {0.0, 0.0};
  sph::SurfaceForce out;
  out.name = "rigid_balance";
  for (int i : support) {
    if (h.fields.fixed[i]) continue;
    in[i] = 1;
    out.particles.push_back(i);
    m += P.mass[i];
    for (int d = 0; d < 2; ++d) c[d] += P.mass[i] * x(i, d);
  }
  if (out.particles.empty()) return out;
  for (double& v : c) v /= m;
  double F[2] = {0.0, 0.0}, M = 0.0, I = 0.0;
  for (int i = 0; i < P.owned_count(); ++i) {
    if (in[i]) {
      I += P.mass[i] * (std::pow(x(i, 0) - c[0], 2) + std::pow(x(i, 1) - c[1], 2));
      continue;
    }
    F[0] += f[3 * i], F[1] += f[3 * i + 1];
    M += (x(i, 0) - c[0]) * f[3 * i + 1] - (x(i, 1) - c[1]) * f[3 * i];
  }
  const double alpha = I > 0.0 ? M / I : 0.0;
  for (int i : out.particles) {
    const double rx = x(i, 0) - c[0], ry = x(i, 1) - c[1];
    out.force.insert(out.force.end(), {-P.mass[i] * (F[0] / m - alpha * ry),
                                       -P.mass[i] * (F[1] / m + alpha * rx), 0.0});
  }
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
  const int n = h.particles.owned_count();
  TransferReport& t = st.transfer;
  PreloadAtParticles pa;
  {
    PhaseTimer::Scope scope(result.timer, "transfer");
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Vec3> X(n);
    for (int i = 0; i < n; ++i) X[i] = h.particles.reference(i);
    pa = sample_preload(preload, pre, X, link.mirror, link.key_path);
    const Holding held = hold(held_conditions(preload, pre, link, X, hold_layers(s, h)), preload,
                              link, h);
    t.held = held.how;
    const sph::InitialStateReport rep =
        put_increment(h, pa, pa.increments() - 1, link.return_to_surface);
    std::vector<materials::Vec6> sigma(h.particles.size(), materials::Vec6::Zero());
    std::copy(pa.final_stress().begin(), pa.final_stress().end(), sigma.begin());
    // Every held boundary takes its static force before any balance is computed: a balance
    // taken while another boundary still lacks its static force would carry that boundary's
    // share of the body's weight and stress.
    for (int b : held.held_boundaries) sph::hold_stress(h.transmitting[b], sigma);
    std::vector<int> support;
    for (int b : held.held_boundaries) {
      const std::vector<int> band = sph::within_reach(h, h.transmitting[b].particles);
      h.forces.push_back(sph::balancing_force(h, h.transmitting[b].name + "_balance", band));
      support.insert(support.end(), band.begin(), band.end());
    }
    for (std::size_t k = 0; k < held.force_layers.size(); ++k)
      h.forces.push_back(sph::balancing_force(h, "held_force_balance_" + std::to_string(k),
                                              sph::within_reach(h, held.force_layers[k])));
    // A body on dashpots has no stiffness against rigid motion, in translation or in rotation:
    // the supporting bands take the resultant and the moment the discretisation leaves.
    if (!support.empty()) h.forces.push_back(rigid_balance(h, support));
    const std::vector<double> ob = sph::out_of_balance(h);
    double worst = 0.0;
    for (int i = 0; i < n; ++i)
      worst = std::max(worst, Vec3(ob[3 * i], ob[3 * i + 1], ob[3 * i + 2]).norm());
    t.out_of_balance = worst / std::max(largest_force(h, pa.final_stress()), 1e-300);
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
    while (h.particles.time < link.settle_time)
      sph::advance(h, std::min(sph::stable_step(h), link.settle_time - h.particles.time));
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
            t.worst_yield_ratio, "), out-of-balance ", t.out_of_balance,
            link.settle_time > 0.0 ? detail::concat(", settle drift ", t.settle_drift) : "");

  explicit_dynamics::SphRun run(h, s, out, result);
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
