// The peridynamic stage of a staged run (stages/explicit_stage.hpp).
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/pd_run.hpp"
#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/pd/relaxation.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include "meshfree/stages/held_conditions.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include "meshfree/stages/stage_run.hpp"
#include <chrono>
#include <cmath>
#include <cstddef>

namespace mf::stages {

namespace {

/// A body load of per-particle forces per volume.
void add_body_load(pd::Loading& loading, const std::string& name, const std::vector<int>& particles,
                   const std::vector<Vec3>& density) {
  pd::BodyLoad l;
  l.name = name;
  l.particles = particles;
  l.densities = density;
  loading.loads.push_back(l);
}

/// The held conditions as the body's loads and constraints; returns how each acts.
std::vector<std::string> hold(const std::vector<HeldCondition>& held, const Preload& preload,
                              const PreloadAtParticles& pa, explicit_dynamics::PdSetup& setup) {
  pd::Model& m = setup.model;
  const particles::ParticleSet& P = m.particles;
  std::vector<std::string> how;
  for (const HeldCondition& h : held) {
    if (h.kind == HeldCondition::Kind::Force || h.kind == HeldCondition::Kind::Body) {
      std::vector<int> particles = h.particles;
      std::vector<Vec3> density;
      Vec3 total = Vec3::Zero();
      if (h.kind == HeldCondition::Kind::Body) {
        particles.resize(P.size());
        for (int i = 0; i < P.size(); ++i) {
          particles[i] = i;
          const Vec3 b = h.body_factor * preload.body_force_at(h.gravity, pa.image[i].x);
          density.push_back(mirrored(b, pa.image[i]));
          total += density.back() * P.volume[i];
        }
      } else {
        for (std::size_t k = 0; k < particles.size(); ++k) {
          density.push_back(h.force[k] / P.volume[particles[k]]);
          total += h.force[k];
        }
      }
      add_body_load(setup.loading, h.name, particles, density);
      how.push_back(detail::concat(h.name, ": constant force on ", particles.size(),
                                   " particles, total ", vector_text(total, preload)));
      continue;
    }
    pd::Constraint c;
    c.name = h.name;
    c.particles = h.particles;
    if (h.kind == HeldCondition::Kind::Clamp) {
      for (int d = 0; d < preload.dimension(); ++d) c.fixed[d] = true;
    } else {
      c.fixed[h.component] = true;
    }
    for (int i : h.particles) c.held.push_back(pa.final_u()[i]);
    setup.loading.constraints.push_back(c);
    const std::string what = h.kind != HeldCondition::Kind::Clamp
                                 ? "xyz"[h.component] + std::string(" component")
                             : preload.dimension() == 2 ? "both components"
                                                        : "all three components";
    how.push_back(detail::concat(h.name, ": ", what, " of ", h.particles.size(),
                                 " particles held at the preload's u"));
  }
  return how;
}

/// Where the held conditions begin among the loads and constraints of a set-up (the stage's own
/// come first).
struct HeldFrom {
  std::size_t loads = 0, constraints = 0;
};

/// The owned members of a held load's or constraint's particle list of the whole body, as this
/// rank's local indices (owned ids are contiguous from local.first_id), and their per-particle
/// values.
template <class T>
void keep_owned(const std::vector<int>& particles, const std::vector<T>& values,
                const explicit_dynamics::PdSetup& local, std::vector<int>& mine,
                std::vector<T>& mine_values) {
  const long owned = local.model.particles.owned_count();
  mine.clear(), mine_values.clear();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const long i = particles[k] - local.first_id;
    if (i < 0 || i >= owned) continue;
    mine.push_back(static_cast<int>(i));
    mine_values.push_back(values[k]);
  }
}

/// Gives this rank's part of the body (`local`) the whole body's displacement and the owned
/// members of its held loads and constraints.
void carry_over(const explicit_dynamics::PdSetup& whole, const HeldFrom& from,
                explicit_dynamics::PdSetup& local) {
  const particles::ParticleSet& W = whole.model.particles;
  particles::ParticleSet& L = local.model.particles;
  std::vector<double> u(3 * static_cast<std::size_t>(L.size()));
  for (int i = 0; i < L.size(); ++i)
    for (int d = 0; d < 3; ++d) u[3 * i + d] = W.u[3 * L.id[i] + d];
  pd::set_displacement(local.model, u);
  for (std::size_t b = from.loads; b < whole.loading.loads.size(); ++b) {
    pd::BodyLoad mine = whole.loading.loads[b];
    keep_owned(whole.loading.loads[b].particles, whole.loading.loads[b].densities, local,
               mine.particles, mine.densities);
    local.loading.loads.push_back(mine);
  }
  for (std::size_t c = from.constraints; c < whole.loading.constraints.size(); ++c) {
    pd::Constraint mine = whole.loading.constraints[c];
    keep_owned(whole.loading.constraints[c].particles, whole.loading.constraints[c].held, local,
               mine.particles, mine.held);
    local.loading.constraints.push_back(mine);
  }
}

double norm_of_difference(const std::vector<double>& a, const std::vector<Vec3>& b,
                          double& norm_b) {
  double d = 0.0, n = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      d += (a[3 * i + k] - b[i][k]) * (a[3 * i + k] - b[i][k]);
      n += b[i][k] * b[i][k];
    }
  norm_b = std::sqrt(n);
  return std::sqrt(d);
}

/// The preload's final state on the whole body with its held conditions; returns the preload at
/// the particles and where the held conditions begin among the set-up's loads and constraints.
PreloadAtParticles transfer(const Preload& preload, const spec::StageLink& link,
                            explicit_dynamics::PdSetup& setup, HeldFrom& held_from,
                            TransferReport& t) {
  const auto t0 = std::chrono::steady_clock::now();
  pd::Model& m = setup.model;
  const std::vector<Vec3> X = reference_positions(m.particles, m.particles.size());
  PreloadAtParticles pa = preload.sample(X, link);
  // A held force acts on the surface layer; a held displacement holds the particles within
  // a horizon of its boundary, so that every free particle keeps its whole bond family; two
  // horizons for a state-based body, whose force on a particle takes its partners' dilatation
  // and so their families too.
  held_from = {setup.loading.loads.size(), setup.loading.constraints.size()};
  const double layer = m.state_based() ? 2.0 * m.horizon : m.horizon;
  t.held = hold(preload.held(link, X, {m.spacing, layer}), preload, pa, setup);
  pd::set_displacement(m, flat(pa.final_u()));
  describe_preload(t, preload, pa, m.particles.volume);
  t.residual_at_uh = pd::residual_ratio(m, setup.state, setup.loading);
  t.seconds = seconds_since(t0);
  return pa;
}

/// The body's own static equilibrium under the held loads, from the preload's displacement (and
/// from zero when the link asks for the comparison): Newton on the linearised bond stiffness, or
/// adaptive dynamic relaxation. No equilibrium is an error naming the link.
void relax(const spec::StageLink& link, const PreloadAtParticles& pa,
           explicit_dynamics::PdSetup& setup, TransferReport& t) {
  pd::Model& m = setup.model;
  pd::RelaxSettings rs;
  rs.tolerance = link.relax_tolerance;
  rs.max_iterations = link.relax_max_iterations;
  const auto equilibrium = [&link, &rs](pd::Model& body, pd::BondState& state,
                                        const pd::Loading& loading) {
    return link.implicit_equilibrium ? pd::solve_statics(body, state, loading, rs)
                                     : pd::relax(body, state, loading, rs);
  };
  if (link.relax_from_zero) {
    pd::Model zero = m;
    pd::BondState state = setup.state;
    pd::set_displacement(zero, std::vector<double>(3 * m.particles.size(), 0.0));
    const pd::RelaxReport z = equilibrium(zero, state, setup.loading);
    t.relax_iterations_from_zero = z.converged ? z.iterations : -1;
    t.relax_seconds_from_zero = z.seconds;
  }
  const pd::RelaxReport r = equilibrium(m, setup.state, setup.loading);
  t.relax_method = link.implicit_equilibrium ? "newton (" + r.solver + ")" : "adr";
  t.relax_linear_iterations = r.linear_iterations;
  MF_REQUIRE(r.converged, link.key_path,
             ": the peridynamic body found no static equilibrium under the held loads within ",
             r.iterations,
             link.implicit_equilibrium ? " Newton iterations (residual ratio "
                                       : " relaxation iterations (residual ratio ",
             r.residual_ratio,
             "); raise transfer.relax_max_iterations or check the held conditions");
  t.relax_iterations = r.iterations;
  t.relax_residual = r.residual_ratio;
  t.out_of_balance = r.residual_ratio;
  t.relax_seconds = r.seconds;
  double norm_uh = 0.0;
  t.pd_vs_galerkin =
      norm_of_difference(m.particles.u, pa.final_u(), norm_uh) / std::max(norm_uh, 1e-300);
}

void log_transfer(const Preload& preload, const TransferReport& t) {
  log::info("transfer: ", t.particles, " particles from stage ", preload.spec().stage,
            ", residual ratio at u^h ", t.residual_at_uh, "; equilibrium by ", t.relax_method,
            " in ", t.relax_iterations, " iterations (from zero: ", t.relax_iterations_from_zero,
            "), |u_PD - u^h| / |u^h| = ", t.pd_vs_galerkin);
}

/// Over several ranks: the body's blocks with their ghosts take the relaxed state and the held
/// conditions of the whole body, made on every rank, and the preload at their own particles.
void spread_over_ranks(const spec::ProblemSpec& stage, const distribution::Ranks& ranks,
                       const HeldFrom& held_from, explicit_dynamics::PdSetup& setup,
                       PreloadAtParticles& pa, PhaseTimer& timer) {
  explicit_dynamics::PdSetup local = explicit_dynamics::build_pd_setup(stage, timer, ranks);
  carry_over(setup, held_from, local);
  pa = select_particles(pa, local.model.particles.id);
  setup = std::move(local);
}

} // namespace

ExplicitStage run_pd_stage(const Preload& preload, const spec::ProblemSpec& stage,
                           const spec::StageLink& link, int index,
                           const explicit_dynamics::RunPlace& place) {
  const spec::PdSpec& s = stage.pd();
  ExplicitStage st;
  explicit_dynamics::PdRunResult result;
  explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(stage, result.timer);
  // `check` refuses an endless stage before anything runs; here it stops before the stage does.
  explicit_dynamics::require_finite_run(explicit_dynamics::planned_run(s, setup),
                                        place.out ? place.out->dir() : ".");
  explicit_dynamics::log_pd_setup(stage, setup);
  st.transfer.peridynamic = true;
  PreloadAtParticles pa;
  HeldFrom held_from;
  {
    PhaseTimer::Scope scope(result.timer, "transfer");
    pa = transfer(preload, link, setup, held_from, st.transfer);
  }
  {
    PhaseTimer::Scope scope(result.timer, "relaxation");
    relax(link, pa, setup, st.transfer);
  }
  log_transfer(preload, st.transfer);
  if (!place.ranks.serial())
    spread_over_ranks(stage, place.ranks, held_from, setup, pa, result.timer);
  result.mpi_ranks = place.ranks.size;
  explicit_dynamics::PdRun run(setup, s, place.out, result);
  pd::Model& m = setup.model;
  const std::vector<double> u0 = m.particles.u; // the relaxed state, back for t = 0
  replay_preload(run, pa.increments(), [&](int k) {
    pd::set_displacement(m, flat(pa.u[k]));
    m.particles.time = pa.pseudo_time[k];
  });
  run_stage(st, run, result, s, link, index, place, [&] {
    pd::set_displacement(m, u0);
    m.particles.time = 0.0;
    pd::accelerate(m, setup.state, setup.loading, false);
  });
  st.displacement = m.particles.u;
  st.position = m.particles.X;
  return st;
}

} // namespace mf::stages
