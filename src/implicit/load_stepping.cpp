#include "meshfree/implicit/load_stepping.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/implicit/point_law.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>

namespace mf::implicit {

namespace {

using Clock = std::chrono::steady_clock;

/// True for a condition whose factor changes something: a nonzero prescribed displacement or
/// traction (a clamp's factor does not matter).
bool drives(const spec::BoundaryCondition& bc) {
  if (bc.value_from_exact || bc.traction_from_exact) return true;
  if (bc.constrains) return !bc.value.cwiseProduct(bc.mask).isZero();
  return bc.pressure_load ? bc.pressure != 0.0 : !bc.traction.isZero();
}

/// The nominal increments of the whole schedule, and how many of them are done when step `s`
/// has come `tau` of its way (a cut increment counts by its share).
double increments_total(const ScheduleSpec& schedule) {
  double n = 0.0;
  for (const spec::LoadStep& step : *schedule.steps) n += step.increments;
  return n;
}

double increments_done(const ScheduleSpec& schedule, std::size_t s, double tau) {
  const auto& steps = *schedule.steps;
  double n = 0.0;
  for (std::size_t k = 0; k < s; ++k) n += steps[k].increments;
  return n + tau * steps[s].increments;
}

} // namespace

ScheduleSpec schedule_of(const spec::ProblemSpec& spec) {
  const auto& galerkin = spec.galerkin();
  ScheduleSpec s;
  s.steps = &galerkin.steps;
  s.nonlinear = galerkin.nonlinear;
  s.fields_every = galerkin.fields_every;
  for (const spec::BoundaryCondition& bc : galerkin.boundary)
    s.driving.push_back(drives(bc) ? bc.name : std::string());
  s.body_force = has_body_force(spec);
  return s;
}

std::string factors_text(const ScheduleSpec& schedule, const std::vector<double>& f) {
  std::string s;
  for (std::size_t c = 0; c < schedule.driving.size(); ++c)
    if (!schedule.driving[c].empty())
      s += (s.empty() ? "" : ", ") + schedule.driving[c] + " " + detail::concat(f[c]);
  if (schedule.body_force) s += (s.empty() ? "" : ", ") + detail::concat("body_force ", f.back());
  return s.empty() ? "no load" : s;
}

namespace {

/// What the increments of a schedule share: the system, Newton, the state and the position,
/// the clock and the increment counts of the progress lines, and the outcome so far.
struct ScheduleRun {
  const ScheduleSpec& spec;
  IncrementalSystem& problem;
  solvers::NonlinearBlockSystem& newton;
  std::vector<double>& d;
  const IncrementDone& done;
  SchedulePosition& at;
  const PositionKept& kept;
  const ReviewIncrement& review;
  solvers::NewtonSettings settings;
  Clock::time_point began;
  double total = 0.0, done_at_start = 0.0;
  ScheduleOutcome o;
};

/// Halves the increment towards `to` after Newton failed there; after the last allowed
/// cut-back, stops the schedule instead and returns false. The increment never falls below
/// 2^-max_cutbacks of its nominal size: near a limit load every tiny increment converges and
/// the next one fails, so a bound on the halvings in a row alone would creep on towards the
/// limit by ever smaller increments, each costing a failed Newton solve.
bool cut_back(ScheduleRun& run, const spec::LoadStep& step, double to,
              const solvers::NewtonReport& rep) {
  SchedulePosition& at = run.at;
  const std::string why = rep.reason + (rep.failure.empty() ? "" : ": " + rep.failure);
  const int most = run.spec.nonlinear.max_cutbacks;
  const double smallest = std::ldexp(1.0 / step.increments, -most);
  // An increment never exceeds its nominal size, so this also bounds the halvings in a row.
  if (0.5 * at.dtau < smallest * (1.0 - 1e-9)) {
    run.o.status = "stopped";
    run.o.stop_reason = detail::concat(
        "step '", step.name, "': the increment to ", to, " of the step did not converge (", why,
        ") at ", at.dtau * step.increments, " of the nominal increment, after ", at.cuts,
        " cut-backs in a row (an increment is cut to 2^-", most,
        " of nominal at most); the last converged state has factors ",
        factors_text(run.spec, at.current),
        ". Under load control this is how a limit load shows: the body cannot carry more; "
        "prescribe a displacement to follow it further.");
    log::warn(run.o.stop_reason);
    return false;
  }
  ++at.cuts;
  at.easy = 0;
  at.dtau *= 0.5;
  log::info("  step '", step.name, "': no convergence towards ", to, " (", why,
            "); cutting the increment to ", at.dtau * step.increments, " of nominal");
  return true;
}

/// Records the converged increment of step `s` that reached `at.tau` with factors `f`, logs
/// the progress line, and grows a cut increment back.
void record_increment(ScheduleRun& run, std::size_t s, const std::vector<double>& f,
                      const solvers::NewtonReport& rep, bool last, double nominal) {
  const ScheduleSpec& spec = run.spec;
  SchedulePosition& at = run.at;
  const std::vector<spec::LoadStep>& steps = *spec.steps;
  const spec::LoadStep& step = steps[s];
  IncrementRecord rec;
  rec.step = static_cast<int>(s);
  rec.step_fraction = at.tau;
  rec.factors = f;
  rec.newton = rep;
  rec.cutbacks = at.cuts;
  const bool step_end = last;
  const bool write_fields =
      ++at.since_output >= spec.fields_every || (step_end && s + 1 == steps.size());
  if (write_fields) at.since_output = 0;
  const IncrementRecord& recorded = run.done(std::move(rec), write_fields);
  const double done_now = increments_done(spec, s, at.tau);
  log::info(
      "  increment ", std::lround(done_now), " of ", std::lround(run.total), ", step '", step.name,
      "' at ", at.tau, " (", factors_text(spec, f), "): ", rep.iterations,
      " Newton iterations, |R|/|F| ", rep.residual.back() / std::max(rep.scale.back(), 1e-300),
      ", plastic points ", recorded.plastic_points, ", max plastic strain ",
      recorded.max_plastic_strain, "; ",
      log::eta(seconds_since(run.began),
               (done_now - run.done_at_start) / std::max(run.total - run.done_at_start, 1e-300)));
  // A cut increment grows back, doubling after every two easy ones, up to the nominal size.
  if (at.dtau < nominal && rep.iterations <= 6 && ++at.easy >= 2) {
    at.dtau = std::min(nominal, 2.0 * at.dtau);
    at.easy = 0;
  }
  at.cuts = 0;
  if (run.kept) run.kept(step_end && s + 1 == steps.size());
}

/// The increments of step at.step from at.tau to its end, or until the schedule stops.
void run_step(ScheduleRun& run) {
  SchedulePosition& at = run.at;
  const std::size_t nf = run.spec.factors();
  const std::size_t s = static_cast<std::size_t>(at.step);
  const spec::LoadStep& step = (*run.spec.steps)[s];
  const double nominal = 1.0 / step.increments;
  if (at.dtau <= 0.0) at.dtau = nominal;
  while (at.tau < 1.0 - 1e-12) {
    at.dtau = std::min(at.dtau, 1.0 - at.tau);
    const bool last = at.tau + at.dtau >= 1.0 - 1e-12;
    const double to = last ? 1.0 : at.tau + at.dtau;
    std::vector<double> f(nf);
    for (std::size_t c = 0; c < nf; ++c) f[c] = at.start[c] + to * (step.target[c] - at.start[c]);
    run.problem.set_factors(f);
    std::vector<double> trial = run.d;
    const auto t0 = Clock::now();
    solvers::NewtonReport rep = run.newton.solve(trial, run.settings);
    run.o.newton_seconds += seconds_since(t0);
    if (!rep.converged) {
      if (!cut_back(run, step, to, rep)) break;
      continue;
    }
    if (run.review && run.review()) {
      // Solved again on another discretisation: its cut-backs start afresh, at this size.
      at.cuts = 0;
      run.o.paused = true;
      return;
    }
    run.d = std::move(trial);
    run.problem.commit();
    at.tau = to;
    at.current = f;
    record_increment(run, s, f, rep, last, nominal);
  }
}

} // namespace

ScheduleOutcome run_load_schedule(const ScheduleSpec& schedule, IncrementalSystem& problem,
                                  solvers::NonlinearBlockSystem& newton, std::vector<double>& d,
                                  const IncrementDone& done, SchedulePosition& at,
                                  const PositionKept& kept, const ReviewIncrement& review,
                                  ScheduleClock* clock) {
  ScheduleRun run{schedule, problem, newton,       d,   done, at, kept,
                  review,   {},      Clock::now(), 0.0, 0.0,  {}};
  const int steps = static_cast<int>(schedule.steps->size());
  if (at.current.empty()) at.current.assign(schedule.factors(), 0.0);
  if (at.start.empty()) at.start = at.current;
  run.settings.tolerance = schedule.nonlinear.tolerance;
  run.settings.max_iterations = schedule.nonlinear.max_iterations;
  run.settings.keep_tangent = schedule.nonlinear.keep_tangent;
  run.total = increments_total(schedule);
  run.done_at_start = at.step < steps ? increments_done(schedule, at.step, at.tau) : run.total;
  if (clock) {
    if (clock->done_at_start < 0.0) clock->done_at_start = run.done_at_start;
    run.began = clock->began;
    run.done_at_start = clock->done_at_start;
  }
  while (at.step < steps && run.o.status == "completed") {
    run_step(run);
    if (run.o.status != "completed" || run.o.paused) break;
    // The next step starts where this one ended.
    ++at.step;
    at.tau = at.dtau = 0.0;
    at.cuts = at.easy = 0;
    at.start = at.current;
  }
  return run.o;
}

} // namespace mf::implicit
