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
bool drives(const io::BoundaryCondition& bc) {
  if (bc.value_from_exact || bc.traction_from_exact) return true;
  if (bc.constrains) return !bc.value.cwiseProduct(bc.mask).isZero();
  return bc.pressure_load ? bc.pressure != 0.0 : !bc.traction.isZero();
}

/// The nominal increments of the whole schedule, and how many of them are done when step `s`
/// has come `tau` of its way (a cut increment counts by its share).
double increments_total(const io::ProblemSpec& spec) {
  double n = 0.0;
  for (const io::LoadStep& step : spec.steps) n += step.increments;
  return n;
}

double increments_done(const io::ProblemSpec& spec, std::size_t s, double tau) {
  double n = 0.0;
  for (std::size_t k = 0; k < s; ++k) n += spec.steps[k].increments;
  return n + tau * spec.steps[s].increments;
}

} // namespace

std::string factors_text(const io::ProblemSpec& spec, const std::vector<double>& f) {
  std::string s;
  for (std::size_t c = 0; c < spec.boundary.size(); ++c)
    if (drives(spec.boundary[c]))
      s += (s.empty() ? "" : ", ") + spec.boundary[c].name + " " + detail::concat(f[c]);
  if (has_body_force(spec)) s += (s.empty() ? "" : ", ") + detail::concat("body_force ", f.back());
  return s.empty() ? "no load" : s;
}

ScheduleOutcome run_load_schedule(const io::ProblemSpec& spec, ElastoplasticSystem& problem,
                                  solvers::NonlinearBlockSystem& newton, std::vector<double>& d,
                                  const IncrementDone& done, SchedulePosition& at,
                                  const PositionKept& kept) {
  ScheduleOutcome o;
  const std::size_t nf = spec.boundary.size() + 1;
  if (at.current.empty()) at.current.assign(nf, 0.0);
  if (at.start.empty()) at.start = at.current;
  std::vector<double>& current = at.current;
  solvers::NewtonSettings settings;
  settings.tolerance = spec.nonlinear.tolerance;
  settings.max_iterations = spec.nonlinear.max_iterations;
  int& since_output = at.since_output;
  const auto began = Clock::now();
  const double total = increments_total(spec);
  const double done_at_start =
      at.step < static_cast<int>(spec.steps.size()) ? increments_done(spec, at.step, at.tau) : total;
  while (at.step < static_cast<int>(spec.steps.size()) && o.status == "completed") {
    const std::size_t s = static_cast<std::size_t>(at.step);
    const io::LoadStep& step = spec.steps[s];
    const std::vector<double>& start = at.start;
    const double nominal = 1.0 / step.increments;
    double& tau = at.tau;
    double& dtau = at.dtau;
    if (dtau <= 0.0) dtau = nominal;
    int& cuts = at.cuts;
    int& easy = at.easy;
    while (tau < 1.0 - 1e-12) {
      dtau = std::min(dtau, 1.0 - tau);
      const bool last = tau + dtau >= 1.0 - 1e-12;
      const double to = last ? 1.0 : tau + dtau;
      std::vector<double> f(nf);
      for (std::size_t c = 0; c < nf; ++c) f[c] = start[c] + to * (step.target[c] - start[c]);
      problem.set_factors(f);
      std::vector<double> trial = d;
      const auto t0 = Clock::now();
      solvers::NewtonReport rep = newton.solve(trial, settings);
      o.newton_seconds += seconds_since(t0);
      if (!rep.converged) {
        const std::string why = rep.reason + (rep.failure.empty() ? "" : ": " + rep.failure);
        if (cuts >= spec.nonlinear.max_cutbacks) {
          o.status = "stopped";
          o.stop_reason = detail::concat(
              "step '", step.name, "': the increment to ", to, " of the step did not converge (",
              why, ") after ", cuts, " cut-backs; the last converged state has factors ",
              factors_text(spec, current),
              ". Under load control this is how a limit load shows: the body cannot carry more; "
              "prescribe a displacement to follow it further.");
          log::warn(o.stop_reason);
          break;
        }
        ++cuts;
        easy = 0;
        dtau *= 0.5;
        log::info("  step '", step.name, "': no convergence towards ", to, " (", why,
                  "); cutting the increment to ", dtau * step.increments, " of nominal");
        continue;
      }
      d = std::move(trial);
      problem.commit();
      tau = to;
      current = f;
      IncrementRecord rec;
      rec.step = static_cast<int>(s);
      rec.step_fraction = tau;
      rec.factors = f;
      rec.newton = rep;
      rec.cutbacks = cuts;
      const bool step_end = last;
      const bool write_fields =
          ++since_output >= spec.fields_every || (step_end && s + 1 == spec.steps.size());
      if (write_fields) since_output = 0;
      const IncrementRecord& recorded = done(std::move(rec), write_fields);
      const double done_now = increments_done(spec, s, tau);
      log::info("  increment ", std::lround(done_now), " of ", std::lround(total), ", step '",
                step.name, "' at ", tau, " (", factors_text(spec, f), "): ", rep.iterations,
                " Newton iterations, |R|/|F| ",
                rep.residual.back() / std::max(rep.scale.back(), 1e-300), ", plastic points ",
                recorded.plastic_points, ", max plastic strain ", recorded.max_plastic_strain,
                "; ",
                log::eta(seconds_since(began),
                         (done_now - done_at_start) / std::max(total - done_at_start, 1e-300)));
      // A cut increment grows back, doubling after every two easy ones, up to the nominal size.
      if (dtau < nominal && rep.iterations <= 6 && ++easy >= 2) {
        dtau = std::min(nominal, 2.0 * dtau);
        easy = 0;
      }
      cuts = 0;
      if (kept) kept(step_end && s + 1 == spec.steps.size());
    }
    if (o.status != "completed") break;
    // The next step starts where this one ended.
    ++at.step;
    at.tau = at.dtau = 0.0;
    at.cuts = at.easy = 0;
    at.start = at.current;
  }
  return o;
}

} // namespace mf::implicit
