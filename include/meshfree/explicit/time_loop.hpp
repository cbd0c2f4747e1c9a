#pragma once
// The time loop of every explicit analysis (peridynamics, SPH): steps to the end time, a history
// row every history_interval, fields every fields_interval and at the end (one field step per
// instant: where two share a time, ParaView's XDMF readers show an empty frame), a progress line
// every tenth of the run and at least every 10 s with an estimate of the time left (and a 100%
// line at the end), and a stop naming the step, time, particle and position when the state stops
// being finite. The model is a template argument, so its functions are called directly (once per
// step each; the particle loops stay inside them):
//   double time() const; long step() const;
//   bool time_step(double remaining, double& dt, std::string& why)  // false: no step (why)
//   void advance(double dt, bool history_due)  // may throw mf::Error: the run stops with it
//   void track()                                // after every step (gauge maxima)
//   int nonfinite() const                       // a particle whose motion is not finite, or -1
//                                               // (over MPI ranks: collective, its global id)
//   Vec3 position(int particle) const           // of the particle nonfinite() named
//   std::string advice() const                  // what a non-finite state suggests
//   void record()                               // a history row at the current instant
//   void write_fields()
//   std::string progress() const                // the model's part of the progress line
//   void save(io::Checkpoints&, const io::Saver&) // its state into a checkpoint
//   void restore(const io::Loader&)             // ... and back, on a restart
// With checkpoints (io/checkpoint.hpp) one is written at the end of every step where it is due,
// holding the model's state and the loop's own (what is due next); a loop given a checkpoint to
// resume from goes on from there as the run it came from would have.
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/core/types.hpp"
#include "meshfree/io/checkpoint.hpp"
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace mf::explicit_dynamics {

struct Schedule {
  double end_time = 0.0;
  double history_interval = 0.0; // <= 0: every step
  double fields_interval = 0.0;  // <= 0: at the start and the end only
};

/// What a loop has still to do, between two steps (a checkpoint keeps it).
struct LoopState {
  double recorded = 0.0; // the instant of the last history row
  double written = 0.0;  // the instant of the last field step
  double next_history = 0.0, next_fields = 0.0;
  double history_interval = 0.0, fields_interval = 0.0; // as scheduled when it was kept
  long steps = 0;
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("recorded", recorded), visit("written", written);
    visit("next_history", next_history);
    visit("next_fields", next_fields), visit("history_interval", history_interval);
    visit("fields_interval", fields_interval), visit("steps", steps);
  }
  /// What a checkpoint held: finite instants at most a million intervals behind t, or the loops
  /// that catch them up would not end.
  bool plausible(double t) const {
    const auto near = [t](double next, double interval) {
      return std::isfinite(next) && next >= 0.0 &&
             (interval <= 0.0 || (std::isfinite(interval) && t - next < 1e6 * interval));
    };
    return std::isfinite(recorded) && recorded <= t && steps >= 0 &&
           near(next_history, history_interval) && near(next_fields, fields_interval);
  }
  /// After a restart whose schedule changed an interval: the next instant is the first multiple
  /// of the new interval after t.
  void reschedule(const Schedule& s, double t) {
    if (s.history_interval != history_interval && s.history_interval > 0.0)
      next_history = next_multiple_after(t, s.history_interval);
    if (s.fields_interval != fields_interval && s.fields_interval > 0.0)
      next_fields = next_multiple_after(t, s.fields_interval);
    history_interval = s.history_interval;
    fields_interval = s.fields_interval;
  }
};

struct LoopReport {
  long steps = 0;               // of the whole run, before a restart included
  long steps_timed = 0;         // taken by this process, in `seconds`
  double seconds = 0.0;         // wall time of the loop
  double advance_seconds = 0.0; // of which in the model's advance()
  std::string status = "completed", stop_reason;
  bool completed() const { return status == "completed"; }
  void stop(std::string reason) {
    status = "failed";
    stop_reason = std::move(reason);
  }
};

/// The loop's progress lines: at every tenth of the simulated time, at least every 10 s of wall
/// time between them, and at the end of a completed run (the 100% line). The model's part of the
/// line may be collective over MPI ranks (a maximum), so it is printed only on the tenths, which
/// every rank reaches at the same step; the wall-time lines are rank 0's own.
class Progress {
public:
  using Clock = std::chrono::steady_clock;
  Progress(double t_begin, double t_end)
      : t_begin_(t_begin), t_end_(t_end), start_(Clock::now()), last_(start_) {
    while (tenth_ <= 10 && reached(t_begin, tenth_)) ++tenth_;
  }
  template <class Model> void update(const Model& model) {
    const double t = model.time();
    if (reached(t, tenth_)) {
      while (tenth_ <= 10 && reached(t, tenth_)) ++tenth_;
      report(model, ", " + model.progress());
    } else if (log::rank() == 0 && seconds(last_) >= 10.0) {
      report(model, "");
    }
  }

private:
  static double seconds(Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
  }
  bool reached(double t, int tenth) const { return t >= 0.1 * tenth * t_end_ * (1.0 - 1e-12); }
  template <class Model> void report(const Model& model, const std::string& model_part) {
    const double t = model.time();
    const double done = t_end_ > t_begin_ ? (t - t_begin_) / (t_end_ - t_begin_) : 1.0;
    char time[32]; // 4 significant digits tell the tenths apart
    std::snprintf(time, sizeof time, "%.4g", t);
    log::info("  t = ", time, " (", static_cast<int>(std::floor(100.0 * t / t_end_ + 1e-6)),
              "%), step ", model.step(), model_part, ", ", log::eta(seconds(start_), done));
    last_ = Clock::now();
  }
  double t_begin_, t_end_;
  int tenth_ = 1; // the next tenth of the end time to report
  Clock::time_point start_, last_;
};

namespace loop {

using Clock = std::chrono::steady_clock;

/// The model's state and the loop's read back from the checkpoint `resume`, the schedule then
/// that of `s`.
template <class Model>
void restore(Model& model, const Schedule& s, const io::StateReader& resume, LoopState& state) {
  try {
    const io::Loader load{resume, ""};
    state.for_each_state(load / "loop");
    model.restore(load);
    io::check_resumed(resume, model.time(), model.step());
    if (!state.plausible(model.time()))
      io::refuse_checkpoint("the checkpoint's schedule of outputs is not that of a run at t = " +
                            detail::concat(model.time()) + " (a damaged checkpoint)");
  } catch (const io::CheckpointRefused& e) {
    io::refused_on_this_rank(e);
    throw;
  }
  state.reschedule(s, model.time());
  log::info("restarted at t = ", model.time(), " (step ", model.step(), ")");
}

/// Where the loop begins: at the checkpoint `resume`, or at the model's present instant,
/// recorded and written.
template <class Model>
LoopState begin(Model& model, const Schedule& s, const io::StateReader* resume) {
  LoopState state;
  if (resume) {
    restore(model, s, *resume, state);
    return state;
  }
  model.track();
  model.record();
  model.write_fields();
  state.recorded = state.written = model.time();
  state.next_history = state.history_interval = s.history_interval;
  state.next_fields = state.fields_interval = s.fields_interval;
  return state;
}

/// The history row due after a step; false (and why) when the state is no longer finite, which
/// is checked where a row is written.
template <class Model>
bool record(Model& model, const Schedule& s, LoopState& state, std::string& why) {
  const int bad = model.nonfinite();
  if (bad >= 0) {
    const Vec3 x = model.position(bad);
    why = detail::concat("the motion became non-finite at step ", model.step(),
                         " (t = ", model.time(), ") at particle ", bad, " at (", x.x(), ", ", x.y(),
                         ", ", x.z(), "); ", model.advice());
    return false;
  }
  model.record();
  state.recorded = model.time();
  if (s.history_interval > 0.0 && state.next_history <= model.time() * (1 + 1e-12))
    state.next_history = next_multiple_after(model.time(), s.history_interval);
  return true;
}

/// The field step due after a step, if one is.
template <class Model> void write_fields(Model& model, const Schedule& s, LoopState& state) {
  if (!(s.fields_interval > 0.0 && model.time() >= state.next_fields * (1 - 1e-12))) return;
  model.write_fields();
  state.written = model.time();
  if (state.next_fields <= model.time() * (1 + 1e-12))
    state.next_fields = next_multiple_after(model.time(), s.fields_interval);
}

/// One step and the outputs due after it; false (and why) when the run stops there.
template <class Model>
bool step(Model& model, const Schedule& s, LoopState& state, LoopReport& r, std::string& why) {
  double dt = 0.0;
  if (!model.time_step(s.end_time - model.time(), dt, why)) return false;
  const bool history_due =
      s.history_interval <= 0.0 || model.time() + dt >= state.next_history * (1 - 1e-12);
  const auto t0 = Clock::now();
  try {
    model.advance(dt, history_due);
  } catch (const Error& e) {
    why = e.what();
    return false;
  }
  r.advance_seconds += seconds_since(t0);
  ++r.steps;
  ++r.steps_timed;
  model.track();
  if (history_due && !record(model, s, state, why)) return false;
  write_fields(model, s, state);
  return true;
}

/// A checkpoint of the model's state and the loop's at the model's present instant.
template <class Model>
void keep(Model& model, io::Checkpoints& checkpoints, LoopState& state, long steps) {
  state.steps = steps;
  checkpoints.write(model.time(), model.step(), [&](io::StateWriter& file) {
    const io::Saver save{file, ""};
    state.for_each_state(save / "loop");
    model.save(checkpoints, save);
  });
}

} // namespace loop

template <class Model>
LoopReport run_time_loop(Model& model, const Schedule& s, io::Checkpoints* checkpoints = nullptr,
                         const io::StateReader* resume = nullptr) {
  LoopReport r;
  LoopState state = loop::begin(model, s, resume);
  r.steps = state.steps;
  Progress progress(model.time(), s.end_time);
  const auto start = loop::Clock::now();
  while (model.time() < s.end_time * (1.0 - 1e-12)) {
    std::string why;
    if (!loop::step(model, s, state, r, why)) {
      r.stop(std::move(why));
      break;
    }
    progress.update(model);
    if (checkpoints && model.time() < s.end_time * (1.0 - 1e-12) && checkpoints->due(model.time()))
      loop::keep(model, *checkpoints, state, r.steps);
  }
  r.seconds = seconds_since(start);
  if (r.completed()) {
    if (state.recorded < model.time()) model.record();
    if (state.written < model.time()) model.write_fields();
  }
  return r;
}

} // namespace mf::explicit_dynamics
