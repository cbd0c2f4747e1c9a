#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/implicit/elastic_limit.hpp"
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/implicit/increment_recorder.hpp"
#include "meshfree/implicit/load_stepping.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>
#include <cmath>
#include <memory>
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

} // namespace

ElastoplasticResult solve_elastoplastic_static(const spec::ProblemSpec& spec,
                                               const solvers::PetscSession& session,
                                               io::OutputDirectory* out, const std::string& dir,
                                               const io::Restart* restart) {
  MF_REQUIRE(!spec.galerkin().steps.empty(), "an elastoplastic analysis needs steps");
  ElastoplasticResult R;
  const auto model =
      std::make_shared<const GalerkinModel>(build_galerkin_model(spec, session, R.timer));
  const GalerkinModel& m = *model;
  R.method = describe_method(spec.galerkin().discretisation, spec.domain);
  count_model(m, session, R);
  find_elastic_limit(spec, m, session, R);

  ElastoplasticSystem problem(spec, m);
  solvers::NonlinearBlockSystem newton(
      session.comm(), R.nodes, m.own, m.pattern.offset, m.pattern.column, problem.needed_nodes(),
      [&](const std::vector<double>& d, double* r, auto& s) { problem.residual(d, r, s); },
      [&](const std::vector<double>& d, solvers::BlockValueArrays values) {
        problem.jacobian(d, values);
      },
      linear_solver_settings(spec, m));
  R.solver = newton.description();
  log::info("Newton: ", R.solver, ", tolerance |R| <= ", spec.galerkin().nonlinear.tolerance,
            " |F|");

  IncrementRecorder recorder(spec, m, session, session.rank() == 0 ? out : nullptr);
  std::vector<double> d(2 * static_cast<std::size_t>(R.nodes), 0.0);
  SchedulePosition at;
  const auto state = checkpoint_state(R, d, problem, at);
  if (restart)
    resume(*restart, spec, session, state, recorder, R, at);
  else
    record_unloaded_state(spec, d, problem, newton, recorder, R);
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
  const ScheduleOutcome o = run_load_schedule(
      schedule_of(spec), problem, newton, d,
      [&](IncrementRecord rec, bool write_fields) -> const IncrementRecord& {
        PhaseTimer::Scope scope(R.timer, "increment_output");
        recorder.record(std::move(rec), d, problem.states(), newton, write_fields, R);
        if (spec.galerkin().initial_stress && R.increments.size() == 2) {
          const double f = std::sqrt(
              solvers::sum_everywhere(session.comm(), problem.initial_stress_imbalance_squared()));
          const solvers::NewtonReport& n = R.increments[1].newton;
          R.initial_out_of_balance = f / std::max(n.scale.back(), 1e-300);
        }
        return R.increments.back();
      },
      at, keep);
  R.checkpoints = checkpoints.counts();
  if (spec.galerkin().initial_stress && R.increments.size() > 1) log_initial_stress(R);
  R.status = o.status;
  R.stop_reason = o.stop_reason;
  R.timer.add("newton", o.newton_seconds);
  R.residual_seconds = problem.residual_seconds();
  R.jacobian_seconds = problem.jacobian_seconds();
  recorder.close();
  keep_converged_state(model, problem, newton, d, session, R);
  if (spec.galerkin().discretisation.adapt)
    R.estimate =
        recovery_error(m, R.state.stress,
                       materials::elastic_matrix(spec.elasticity(), spec.model).inverse(), session);
  R.memory = solvers::peak_memory(session.comm());
  return R;
}

} // namespace mf::implicit
