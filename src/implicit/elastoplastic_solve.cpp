#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/implicit/elastic_limit.hpp"
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/implicit/increment_recorder.hpp"
#include "meshfree/implicit/load_stepping.hpp"
#include "meshfree/implicit/state_transfer.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <type_traits>

namespace mf::implicit {

namespace {

/// Counts of the model, summed over the ranks where each rank holds a share.
void count_model(const GalerkinModel& m, const solvers::PetscSession& session,
                 ElastoplasticResult& R) {
  R.nodes = m.node_count();
  R.dofs = 2 * R.nodes;
  R.domain_points = static_cast<int>(m.domain.x.size());
  R.cells = m.domain.cell_count;
  R.boundary_points = 0;
  for (const auto& c : m.conditions) R.boundary_points += static_cast<int>(c.points.x.size());
  R.matrix_nonzeros =
      solvers::sum_everywhere(session.comm(), 4.0 * static_cast<double>(m.pattern.column.size()));
  log::info("integration: ", R.cells, " background cells, ", R.domain_points, " domain points, ",
            R.boundary_points, " boundary points");
}

void log_elastic_limit(const spec::ProblemSpec& spec, const ElasticLimit& e) {
  if (!e.skipped.empty()) {
    log::info("first yield is not searched: ", e.skipped);
    return;
  }
  const PeakStress& g = e.gauss_points;
  const PeakStress& n = e.nodes;
  log::info("first yield at ", e.fraction, " of step '", spec.galerkin().steps.front().name, "' (",
            factors_text(schedule_of(spec), e.factors),
            "); elastic von Mises at its end: ", g.von_mises, " at the Gauss point (", g.at.x(),
            ", ", g.at.y(), "), ", n.von_mises, " at the node (", n.at.x(), ", ", n.at.y(), ")");
}

/// The first yield of the first load step, searched on all ranks and logged.
void find_elastic_limit(const spec::ProblemSpec& spec, const GalerkinModel& m,
                        const solvers::PetscSession& session, ElastoplasticResult& R) {
  PhaseTimer::Scope scope(R.timer, "elastic_limit");
  session.collective([&] { R.elastic_limit = elastic_limit(spec, m, session); });
  log_elastic_limit(spec, R.elastic_limit);
}

/// The increments and the rows of every line sampled so far (rank 0), visited one by one.
auto recorded_rows(ElastoplasticResult& R) {
  return [&R](const auto& visit) {
    io::visit_list(visit, "increments", R.increments,
                   [](const auto& at, IncrementRecord& rec) { rec.for_each_state(at); });
    io::visit_list(visit, "lines", R.lines, [](const auto& at, auto& line) {
      at("name", line.first);
      io::visit_list(at, "rows", line.second,
                     [](const auto& row_at, std::vector<double>& row) { row_at("values", row); });
    });
  };
}

/// What a checkpoint keeps besides the field series: every rank's share of the state, the
/// schedule's position and the increments recorded so far (packed into one array).
auto checkpoint_state(ElastoplasticResult& R, std::vector<double>& d, ElastoplasticSystem& problem,
                      SchedulePosition& at) {
  return [&R, &d, &problem, &at](const auto& visit) {
    io::visit_count(visit, "nodes", static_cast<long>(R.nodes));
    io::visit_count(visit, "integration points", static_cast<long>(R.domain_points));
    visit("d", d);
    problem.for_each_state(visit / "system");
    at.for_each_state(visit / "schedule");
    visit("initial_out_of_balance", R.initial_out_of_balance);
    std::vector<char> packed;
    if constexpr (std::decay_t<decltype(visit)>::loads) {
      visit("records", packed);
      std::size_t read = 0;
      recorded_rows(R)(io::Unpacker{packed, read});
    } else {
      recorded_rows(R)(io::Packer{packed});
      visit("records", packed);
    }
  };
}

/// Loads the state of a checkpoint on this rank and logs where the schedule resumes.
template <class State>
void resume(const io::Restart& restart, const spec::ProblemSpec& spec,
            const solvers::PetscSession& session, const State& state, IncrementRecorder& recorder,
            const ElastoplasticResult& R, const SchedulePosition& at) {
  try {
    const auto file = restart.open(session.rank());
    const io::Loader load{*file, ""};
    state(load);
    recorder.restore(load / "recorder");
    const long done = static_cast<long>(R.increments.size()) - 1;
    io::check_resumed(*file, static_cast<double>(done), done);
  } catch (const io::CheckpointRefused& e) {
    io::refused_on_this_rank(e);
    throw;
  }
  log::info(
      "restarted after increment ", R.increments.size() - 1, " (step '",
      spec.galerkin().steps[std::min<std::size_t>(at.step, spec.galerkin().steps.size() - 1)].name,
      "' at ", at.tau, ")");
}

/// Increment 0: the unloaded state.
void record_unloaded_state(const spec::ProblemSpec& spec, const std::vector<double>& d,
                           const ElastoplasticSystem& problem,
                           const solvers::NonlinearBlockSystem& newton, IncrementRecorder& recorder,
                           ElastoplasticResult& R) {
  IncrementRecord zero;
  zero.factors.assign(spec.galerkin().boundary.size() + 1, 0.0);
  zero.newton.converged = true;
  recorder.record(zero, d, problem.states(), newton, false, R);
}

void log_initial_stress(const ElastoplasticResult& R) {
  // The first increment is the equilibrium iteration at the full body force. The system
  // still holds its converged stress unless later increments followed.
  const solvers::NewtonReport& n = R.increments[1].newton;
  log::info("initial stress: equilibrium iteration in ", n.iterations,
            " Newton iterations, |R(0)|/|F| = ", n.residual.front() / n.scale.front(),
            " (support reactions included), out-of-balance of the initial stress ",
            R.initial_out_of_balance);
}

/// The converged state, for whatever comes next.
void keep_converged_state(const std::shared_ptr<const GalerkinModel>& model,
                          const ElastoplasticSystem& problem,
                          const solvers::NonlinearBlockSystem& newton, const std::vector<double>& d,
                          const solvers::PetscSession& session, ElastoplasticResult& R) {
  const PointStates& st = problem.states();
  R.state.parameters = newton.gather_on_root(d);
  solvers::broadcast(session.comm(), R.state.parameters, 0);
  R.state.factors = R.increments.back().factors;
  R.state.history = st.committed;
  R.state.stress = st.committed_stress;
  R.state.stress_zz = st.committed_stress_zz;
  R.state.model = model;
}

/// One discretisation of the body as the solve uses it: the spec of its cloud, the model, the
/// system and Newton on it. Lives where it was made (Newton calls the system).
struct Discretised {
  /// A model with the spec it was built from: its conditions point into that spec, so the
  /// model handed out (ElastoplasticState::model) keeps the spec alive with it.
  struct SpecAndModel {
    spec::ProblemSpec spec;
    GalerkinModel model;
  };
  explicit Discretised(std::shared_ptr<SpecAndModel> both)
      : spec(both->spec), model(both, &both->model) {}
  const spec::ProblemSpec& spec;
  std::shared_ptr<const GalerkinModel> model;
  std::unique_ptr<ElastoplasticSystem> problem;
  std::unique_ptr<solvers::NonlinearBlockSystem> newton;
};

/// The model, system and Newton of `spec`, counted into R.
std::unique_ptr<Discretised> discretise(const spec::ProblemSpec& spec,
                                        const solvers::PetscSession& session, PhaseTimer& timer,
                                        ElastoplasticResult& R) {
  auto both = std::make_shared<Discretised::SpecAndModel>();
  both->spec = spec;
  both->model = build_galerkin_model(both->spec, session, timer);
  auto now = std::make_unique<Discretised>(both);
  const GalerkinModel& m = *now->model;
  count_model(m, session, R);
  now->problem = std::make_unique<ElastoplasticSystem>(now->spec, m);
  ElastoplasticSystem& problem = *now->problem;
  now->newton = std::make_unique<solvers::NonlinearBlockSystem>(
      session.comm(), R.nodes, m.own, m.pattern.offset, m.pattern.column, problem.needed_nodes(),
      [&problem](const std::vector<double>& d, double* r, auto& s) { problem.residual(d, r, s); },
      [&problem](const std::vector<double>& d, solvers::BlockValueArrays values) {
        problem.jacobian(d, values);
      },
      linear_solver_settings(now->spec, m));
  return now;
}

/// The recovery estimate of a stress at the points of a discretisation (its committed or its
/// trial stress).
ErrorEstimate estimate_of(const Discretised& now, const std::vector<Vec3>& stress,
                          const solvers::PetscSession& session) {
  const spec::ProblemSpec& spec = now.spec;
  return recovery_error(*now.model, stress,
                        materials::elastic_matrix(spec.elasticity(), spec.model).inverse(),
                        session);
}

/// The residual and tangent seconds of the Newton solves over the systems a solve goes through:
/// what a system spent before it was taken up (balancing a carried state, the adapt phase's) is
/// not counted.
struct NewtonParts {
  double residual = 0.0, jacobian = 0.0;           // the systems left so far
  double residual_from = 0.0, jacobian_from = 0.0; // the present one's when it was taken up
  void take_up(const ElastoplasticSystem& s) {
    residual_from = s.residual_seconds(), jacobian_from = s.jacobian_seconds();
  }
  void leave(const ElastoplasticSystem& s) {
    residual += s.residual_seconds() - residual_from;
    jacobian += s.jacobian_seconds() - jacobian_from;
  }
};

/// Refinement during the analysis (discretisation.adapt.every): every `every`-th increment, once
/// converged and before it is committed, is estimated; above the target, the marked nodes' cloud
/// is built, the state at the increment's start carried to it and balanced there at the load of
/// that start, and the increment is solved again on it (and estimated again).
class Refiner {
public:
  Refiner(const spec::ProblemSpec& spec, const solvers::PetscSession& session)
      : session_(session), adapt_(spec.galerkin().discretisation.adapt) {
    if (!active()) return;
    record_.refinement = spec.galerkin().discretisation.refinement;
    cloud_ = geometry::generate_nodes(spec.domain, spec.galerkin().discretisation.spacing,
                                      record_.refinement);
  }
  bool active() const { return adapt_ && adapt_->every > 0; }

  /// Increment k (counted from 1), converged on `now`: true when it is to be solved again on a
  /// refined cloud (then refine() builds it), after its trial stress was estimated (every
  /// `every`-th increment while refinement has not ended).
  bool review(const Discretised& now, long k, ElastoplasticResult& R) {
    if (!active() || !record_.ended.empty() || k % adapt_->every != 0) return false;
    if (adapt_->until > 0 && k > adapt_->until) {
      record_.ended = "until reached";
      log::info("adapt: refinement ends after increment ", adapt_->until,
                " (until); the schedule goes on on the cloud of ", now.model->node_count(),
                " nodes");
      return false;
    }
    const auto began = std::chrono::steady_clock::now();
    const ErrorEstimate e = estimate_of(now, now.problem->states().stress, session_);
    AdaptPass pass;
    pass.nodes = now.model->node_count();
    pass.estimate = e.relative();
    pass.increment = static_cast<int>(k);
    const int refinements = static_cast<int>(record_.passes.size()) - unrefined_;
    if (pass.estimate > adapt_->target && refinements + 1 >= adapt_->passes)
      record_.ended = "passes used";
    if (pass.estimate > adapt_->target && record_.ended.empty()) {
      pending_ = next_cloud(now.spec, cloud_, record_.refinement, e);
      if (!pending_->allowed) record_.ended = "max_nodes reached", pending_.reset();
    }
    if (!pending_) ++unrefined_;
    pass.seconds = seconds_since(began);
    log::info("adapt: increment ", k, " on ", pass.nodes, " nodes, estimated error ", pass.estimate,
              " (target ", adapt_->target, ")",
              pending_ ? detail::concat(": ", pending_->marked.size(), " nodes marked")
                       : std::string(record_.ended.empty() ? "" : ": " + record_.ended));
    record_.passes.push_back(pass);
    R.timer.add("adapt", pass.seconds);
    return pending_.has_value();
  }

  /// The discretisation review() asked for, with the state at the increment's start on `now`
  /// (d, the committed history, the load factors `start`) carried to it and in equilibrium (d
  /// too); null when no equilibrium was found there (refinement then ends, logged).
  std::unique_ptr<Discretised> refine(const Discretised& now, std::vector<double>& d,
                                      const std::vector<double>& start, ElastoplasticResult& R) {
    MF_REQUIRE(pending_, "adapt: no refinement was asked for");
    const auto began = std::chrono::steady_clock::now();
    NextCloud cloud = std::move(*pending_);
    pending_.reset();
    const int marked = static_cast<int>(cloud.marked.size());
    std::unique_ptr<Discretised> next = carried(now, std::move(cloud), d, start, R);
    AdaptPass& pass = record_.passes.back();
    if (next)
      pass.marked = marked;
    else
      ++unrefined_;
    const double seconds = seconds_since(began);
    pass.seconds += seconds;
    R.timer.add("adapt", seconds);
    return next;
  }

  /// The record of the refinement at the end of the schedule, with the final estimate.
  Adaptation finish(const Discretised& now, const ErrorEstimate& final_estimate) {
    record_.nodes = now.model->node_count();
    if (record_.ended.empty())
      record_.ended =
          final_estimate.relative() <= adapt_->target ? "target reached" : "increments ended";
    return record_;
  }

private:
  /// The discretisation of `cloud` with the state of `now` carried to it and in equilibrium.
  std::unique_ptr<Discretised> carried(const Discretised& now, NextCloud cloud,
                                       std::vector<double>& d, const std::vector<double>& start,
                                       ElastoplasticResult& R) {
    spec::ProblemSpec spec = now.spec;
    spec.galerkin().discretisation.refinement = cloud.refinement;
    PhaseTimer build; // inside the adapt phase
    std::unique_ptr<Discretised> next;
    try { // the model's errors reach every rank
      next = discretise(spec, session_, build, R);
      // The output evaluates u^h at the nodes (the same on every rank): a node that too few
      // supports cover ends the refinement here rather than the run later.
      shapes_at(*next->model, next->model->node_positions(), false);
    } catch (const Error& e) {
      return stay(now, detail::concat("the refined cloud cannot be used (", e.what(), ")"),
                  "refined cloud not usable", R);
    }
    const std::vector<double> all = now.newton->gather_on_root(d);
    std::vector<double> everywhere = all;
    solvers::broadcast(session_.comm(), everywhere, 0);
    CarriedState c;
    try { // the same fit on every rank: it fails on all of them or none
      c = carry_state(now.spec, *now.model, now.problem->states(), everywhere, *next->model,
                      session_);
    } catch (const Error& e) {
      return stay(
          now, detail::concat("the state cannot be carried to the refined cloud (", e.what(), ")"),
          "refined cloud not usable", R);
    }
    next->problem->set_factors(start);
    const Balance b = carried_balance(*next, c);
    if (!b.found) // the state of `now` is the last converged one
      return stay(now,
                  detail::concat("the state carried to the refined cloud of ",
                                 next->model->node_count(),
                                 " nodes found no equilibrium at the load of the increment's "
                                 "start (",
                                 b.why, ")"),
                  "no equilibrium on the refined cloud", R);
    log::info("adapt: state carried to ", next->model->node_count(), " nodes (", c.copied,
              " points kept, ", c.nearest, " from their nearest), equilibrium in ", b.iterations,
              " Newton iterations",
              b.steps > 1 ? detail::concat(" over ", b.steps, " steps") : std::string());
    d = std::move(c.d);
    record_.refinement = std::move(cloud.refinement);
    cloud_ = std::move(cloud.cloud);
    return next;
  }

  /// Says why the analysis goes on on the cloud of `now`, which ends the refinement.
  std::unique_ptr<Discretised> stay(const Discretised& now, const std::string& why,
                                    const char* ended, ElastoplasticResult& R) {
    log::warn("adapt: ", why, "; the analysis goes on on the cloud of ", now.model->node_count(),
              " nodes, without further refinement");
    record_.ended = ended;
    count_model(*now.model, session_, R);
    return nullptr;
  }

  struct Balance {
    bool found = false;
    int iterations = 0, steps = 0;
    std::string why; // when not found
  };

  /// Equilibrium of the carried state on `next` at the load it is set to, from d:
  /// Newton; where that fails, the carried state's out-of-balance taken away in steps of a
  /// quarter, each committed (a failed step halved, down to 1/64, and doubled again after an
  /// easy one), so that plastic flow follows the way back to balance. The state and d end in
  /// equilibrium when found.
  Balance rebalance(Discretised& next, std::vector<double>& d) const {
    const spec::NonlinearSpec& n = next.spec.galerkin().nonlinear;
    solvers::NewtonSettings settings;
    settings.tolerance = n.tolerance;
    settings.max_iterations = n.max_iterations;
    settings.keep_tangent = n.keep_tangent;
    Balance b;
    const auto solve = [&] {
      std::vector<double> trial = d;
      const solvers::NewtonReport rep = next.newton->solve(trial, settings);
      b.iterations += rep.iterations;
      if (!rep.converged) {
        b.why = rep.reason + (rep.failure.empty() ? "" : ": " + rep.failure);
        return false;
      }
      d = std::move(trial);
      next.problem->commit();
      ++b.steps;
      return true;
    };
    b.found = solve();
    if (b.found) return b;
    log::info("adapt: no equilibrium of the carried state at once (", b.why,
              "); its out-of-balance is taken away in steps");
    std::vector<double> r0(2 * static_cast<std::size_t>(next.model->pattern.rows()));
    long failed = 0;
    try {
      solvers::ResidualSums sums;
      next.problem->residual(d, r0.data(), sums);
    } catch (const Error&) {
      failed = 1;
    }
    if (solvers::sum_everywhere(session_.comm(), failed) > 0) return b;
    double done = 0.0, step = 0.25;
    while (!b.found && step >= 1.0 / 64.0) {
      const double to = std::min(1.0, done + step);
      next.problem->hold_imbalance(r0, 1.0 - to);
      const int before = b.iterations;
      if (!solve()) {
        step *= 0.5;
        continue;
      }
      done = to;
      b.found = done >= 1.0;
      log::info("adapt: ", done, " of the carried state's out-of-balance taken away, ",
                b.iterations, " Newton iterations so far");
      if (b.iterations - before <= 6) step = std::min(0.25, 2.0 * step); // an easy step
    }
    next.problem->hold_imbalance({}, 0.0);
    return b;
  }

  /// Equilibrium of the state c carried to `next` (its parameters c.d balanced in place).
  /// Equilibrium closes the gaps the fitted u^h leaves at the penalty-held boundaries, and the
  /// strain that closes them moves the carried stress; carried again on the balanced u^h, the
  /// stress of the yielded points is the old one there, and mostly its own out-of-balance is
  /// left (the strip pulled to its limit and refined at v = 0.098 from 188 to 270 nodes: the
  /// force at v = 0.1 5.8% low with the stress of the fitted u^h's strain, 1.3% so).
  Balance carried_balance(Discretised& next, CarriedState& c) const {
    Balance b;
    for (int pass = 0; pass < 3 && (pass == 0 || b.found); ++pass) {
      next.problem->start_from(history_keeping_stress(c, *next.model, c.d));
      const Balance r = rebalance(next, c.d);
      b.found = r.found, b.why = r.why;
      b.iterations += r.iterations;
      if (pass == 0) b.steps = r.steps; // the out-of-balance's steps, taken on the first pass
    }
    return b;
  }

  const solvers::PetscSession& session_;
  const std::optional<spec::AdaptSpec>& adapt_;
  Adaptation record_;
  geometry::NodeCloud cloud_;        // the present cloud, as its boxes make it (nominal spacings)
  int unrefined_ = 0;                // estimates that left the cloud as it was
  std::optional<NextCloud> pending_; // asked for by review()
};

/// The load schedule on `now`, each increment reviewed by `refiner` and solved again on the
/// refined discretisation it asks for (which `now` and the recorder then move to); R gets the
/// Newton solves' residual and tangent seconds over all of them.
ScheduleOutcome run_refining(std::unique_ptr<Discretised>& now, Refiner& refiner,
                             IncrementRecorder& recorder, std::vector<double>& d,
                             const IncrementDone& done, SchedulePosition& at,
                             const PositionKept& keep, ElastoplasticResult& R) {
  const auto review = [&] {
    return refiner.review(*now, static_cast<long>(R.increments.size()), R);
  };
  NewtonParts newton_parts;
  ScheduleClock clock;
  ScheduleOutcome o;
  for (;;) {
    const ScheduleOutcome part = run_load_schedule(schedule_of(now->spec), *now->problem,
                                                   *now->newton, d, done, at, keep, review, &clock);
    o.status = part.status, o.stop_reason = part.stop_reason;
    o.newton_seconds += part.newton_seconds;
    if (!part.paused) break;
    // The increment under way is solved again, on the refined cloud where there is one.
    std::unique_ptr<Discretised> next = refiner.refine(*now, d, at.current, R);
    if (!next) continue;
    recorder.move_to(next->spec, *next->model);
    newton_parts.leave(*now->problem);
    newton_parts.take_up(*next->problem);
    now = std::move(next);
  }
  newton_parts.leave(*now->problem);
  R.residual_seconds = newton_parts.residual;
  R.jacobian_seconds = newton_parts.jacobian;
  return o;
}

} // namespace

ElastoplasticResult solve_elastoplastic_static(const spec::ProblemSpec& spec,
                                               const solvers::PetscSession& session,
                                               io::OutputDirectory* out, const std::string& dir,
                                               const io::Restart* restart) {
  MF_REQUIRE(!spec.galerkin().steps.empty(), "an elastoplastic analysis needs steps");
  ElastoplasticResult R;
  std::unique_ptr<Discretised> now = discretise(spec, session, R.timer, R);
  R.method = describe_method(spec.galerkin().discretisation, spec.domain);
  find_elastic_limit(spec, *now->model, session, R);
  R.solver = now->newton->description();
  log::info("Newton: ", R.solver, ", tolerance |R| <= ", spec.galerkin().nonlinear.tolerance,
            " |F|");

  IncrementRecorder recorder(now->spec, *now->model, session, session.rank() == 0 ? out : nullptr);
  std::vector<double> d(2 * static_cast<std::size_t>(R.nodes), 0.0);
  SchedulePosition at;
  const auto state = checkpoint_state(R, d, *now->problem, at);
  if (restart)
    resume(*restart, spec, session, state, recorder, R, at);
  else
    record_unloaded_state(spec, d, *now->problem, *now->newton, recorder, R);
  // The checkpoints' clock counts converged increments.
  io::Checkpoints checkpoints(dir, distribution::Ranks::of(session.comm()),
                              spec.galerkin().checkpoint, spec.settings, restart);
  const auto keep = [&](bool finished) {
    const long done = static_cast<long>(R.increments.size()) - 1;
    if (finished || !checkpoints.due(static_cast<double>(done))) return;
    PhaseTimer::Scope scope(R.timer, "checkpoints");
    checkpoints.write(static_cast<double>(done), done, [&](io::StateWriter& file) {
      const io::Saver save{file, ""};
      recorder.save(checkpoints, save / "recorder");
      state(save);
    });
  };
  const auto done = [&](IncrementRecord rec, bool write_fields) -> const IncrementRecord& {
    PhaseTimer::Scope scope(R.timer, "increment_output");
    recorder.record(std::move(rec), d, now->problem->states(), *now->newton, write_fields, R);
    if (spec.galerkin().initial_stress && R.increments.size() == 2) {
      const double f = std::sqrt(solvers::sum_everywhere(
          session.comm(), now->problem->initial_stress_imbalance_squared()));
      const solvers::NewtonReport& n = R.increments[1].newton;
      R.initial_out_of_balance = f / std::max(n.scale.back(), 1e-300);
    }
    return R.increments.back();
  };
  Refiner refiner(spec, session);
  // The checkpoint's state refers to the first discretisation: a run that changes it writes none
  // (the input refuses checkpoints with adapt.every).
  MF_REQUIRE(!refiner.active() || !spec.galerkin().checkpoint.any(),
             "adapt.every: no checkpoints are written when the cloud changes");
  const ScheduleOutcome o = run_refining(now, refiner, recorder, d, done, at, keep, R);
  R.checkpoints = checkpoints.counts();
  if (spec.galerkin().initial_stress && R.increments.size() > 1) log_initial_stress(R);
  R.status = o.status;
  R.stop_reason = o.stop_reason;
  R.timer.add("newton", o.newton_seconds);
  recorder.close();
  keep_converged_state(now->model, *now->problem, *now->newton, d, session, R);
  if (spec.galerkin().discretisation.adapt)
    R.estimate = estimate_of(*now, now->problem->states().committed_stress, session);
  if (refiner.active()) R.adaptation = refiner.finish(*now, R.estimate);
  R.memory = solvers::peak_memory(session.comm());
  return R;
}

} // namespace mf::implicit
