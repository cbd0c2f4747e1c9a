#pragma once
// The load schedule of a quasi-static analysis: each step moves the load factors linearly from
// where the last step left them to its targets in increments, each solved by Newton; an
// increment that does not converge is halved and retried, and a cut increment grows back after
// easy ones.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/implicit/incremental_system.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace mf::implicit {

/// How the schedule ended.
struct ScheduleOutcome {
  std::string status = "completed"; // or "stopped": an increment failed after every cut-back
  std::string stop_reason;
  double newton_seconds = 0.0; // in Newton solves
  bool paused = false;         // an increment discarded at `review`'s request
};

/// Where the schedule is between two increments: what a checkpoint keeps of it.
struct SchedulePosition {
  int step = 0;                       // the step under way
  double tau = 0.0, dtau = 0.0;       // how far through it, and the next increment's size
  int cuts = 0, easy = 0;             // cut-backs of the increment, easy increments since one
  int since_output = 0;               // increments since the last field output
  std::vector<double> start, current; // load factors at the step's start and now (empty: zero)
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("step", step), visit("tau", tau), visit("dtau", dtau), visit("cuts", cuts);
    visit("easy", easy), visit("since_output", since_output), visit("start", start);
    visit("current", current);
  }
};

/// What a schedule needs of its problem, plane or 3D: the steps, the Newton controls, how often
/// fields are written, and for each condition its name if its factor drives the body (empty for
/// a clamp, whose factor changes nothing), then whether there is a body force.
struct ScheduleSpec {
  const std::vector<spec::LoadStep>* steps = nullptr;
  spec::NonlinearSpec nonlinear;
  int fields_every = 1;
  std::vector<std::string> driving; // per condition: its name, or empty
  bool body_force = false;
  std::size_t factors() const { return driving.size() + 1; }
};
/// The schedule of a plane Galerkin problem.
ScheduleSpec schedule_of(const spec::ProblemSpec& spec);

/// Called with each converged increment (the system committed, `d` converged) and whether the
/// fields are due; returns the increment as recorded.
using IncrementDone = std::function<const IncrementRecord&(IncrementRecord rec, bool write_fields)>;
/// Called after each converged increment, once `at` holds the position after it; `finished` is
/// true after the schedule's last increment.
using PositionKept = std::function<void(bool finished)>;

/// Asked after each increment's Newton converged, before it is committed: true discards the
/// increment and returns, paused, at the position before it, so that the caller may change the
/// discretisation (the state at the increment's start) and go on from `at`, which solves the
/// increment again.
using ReviewIncrement = std::function<bool()>;

/// The clock of the progress lines: when the schedule began in this process and how many
/// increments were done then (negative: not yet known), kept across the calls of a schedule that
/// pauses.
struct ScheduleClock {
  std::chrono::steady_clock::time_point began = std::chrono::steady_clock::now();
  double done_at_start = -1.0;
};

/// Runs the schedule's steps from `at` (the unloaded state: a default position) and the state in
/// `d`; `d` ends at the last converged state and `at` at its position. `clock` (when given)
/// carries the progress lines' clock from one call to the next.
ScheduleOutcome run_load_schedule(const ScheduleSpec& schedule, IncrementalSystem& problem,
                                  solvers::NonlinearBlockSystem& newton, std::vector<double>& d,
                                  const IncrementDone& done, SchedulePosition& at,
                                  const PositionKept& kept = {}, const ReviewIncrement& review = {},
                                  ScheduleClock* clock = nullptr);

/// "pull 0.002, tension 308": the factors of the conditions that drive the body.
std::string factors_text(const ScheduleSpec& schedule, const std::vector<double>& f);

} // namespace mf::implicit
