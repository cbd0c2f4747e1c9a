#pragma once
// The time loop of every explicit analysis (peridynamics, SPH): steps to the end time, a history
// row every history_interval, fields every fields_interval and at the end (one field step per
// instant: where two share a time, ParaView's XDMF readers show an empty frame), a progress line
// every tenth of the run with an estimate of the time left, and a stop naming the step, time,
// particle and position when the state stops being finite. The model is a template argument, so its
// functions are called directly (once per step each; the particle loops stay inside them):
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
#include <string>

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
};

template <class Model>
LoopReport run_time_loop(Model& model, const Schedule& s, io::Checkpoints* checkpoints = nullptr,
                         const io::StateReader* resume = nullptr) {
  using Clock = std::chrono::steady_clock;
  LoopReport r;
  const auto stop = [&r](std::string reason) {
    r.status = "failed";
    r.stop_reason = std::move(reason);
  };
  LoopState state;
  if (resume) {
    const io::Loader load{*resume, ""};
    state.for_each_state(load / "loop");
    model.restore(load);
    state.reschedule(s, model.time());
    log::info("restarted at t = ", model.time(), " (step ", model.step(), ")");
  } else {
    model.track();
    model.record();
    model.write_fields();
    state.recorded = state.written = model.time();
    state.next_history = state.history_interval = s.history_interval;
    state.next_fields = state.fields_interval = s.fields_interval;
  }
  double& recorded = state.recorded;
  double& next_history = state.next_history;
  double& next_fields = state.next_fields;
  double next_progress = 0.1 * s.end_time;
  while (next_progress <= model.time()) next_progress += 0.1 * s.end_time;
  r.steps = state.steps;
  const double t_begin = model.time();
  const auto start = Clock::now();
  while (model.time() < s.end_time * (1.0 - 1e-12)) {
    double dt = 0.0;
    std::string why;
    if (!model.time_step(s.end_time - model.time(), dt, why)) {
      stop(why);
      break;
    }
    const bool history_due =
        s.history_interval <= 0.0 || model.time() + dt >= next_history * (1 - 1e-12);
    const auto t0 = Clock::now();
    try {
      model.advance(dt, history_due);
    } catch (const Error& e) {
      stop(e.what());
      break;
    }
    r.advance_seconds += seconds_since(t0);
    ++r.steps;
    ++r.steps_timed;
    model.track();
    if (history_due) {
      // Checked where a row is written: a state that is no longer finite stops the run there.
      const int bad = model.nonfinite();
      if (bad >= 0) {
        const Vec3 x = model.position(bad);
        stop(detail::concat("the motion became non-finite at step ", model.step(),
                            " (t = ", model.time(), ") at particle ", bad, " at (", x.x(), ", ",
                            x.y(), ", ", x.z(), "); ", model.advice()));
        break;
      }
      model.record();
      recorded = model.time();
      if (s.history_interval > 0.0 && next_history <= model.time() * (1 + 1e-12))
        next_history = next_multiple_after(model.time(), s.history_interval);
    }
    if (s.fields_interval > 0.0 && model.time() >= next_fields * (1 - 1e-12)) {
      model.write_fields();
      state.written = model.time();
      if (next_fields <= model.time() * (1 + 1e-12))
        next_fields = next_multiple_after(model.time(), s.fields_interval);
    }
    if (model.time() >= next_progress) {
      const double elapsed = seconds_since(start);
      const double left = elapsed * (s.end_time - model.time()) / (model.time() - t_begin);
      log::info("  t = ", model.time(), " (",
                static_cast<int>(std::lround(100 * model.time() / s.end_time)), "%), step ",
                model.step(), ", ", model.progress(), ", ", elapsed, " s, about ", left, " s left");
      next_progress += 0.1 * s.end_time;
    }
    if (checkpoints && model.time() < s.end_time * (1.0 - 1e-12) &&
        checkpoints->due(model.time())) {
      state.steps = r.steps;
      checkpoints->write(model.time(), model.step(), [&](io::StateWriter& file) {
        const io::Saver save{file, ""};
        state.for_each_state(save / "loop");
        model.save(*checkpoints, save);
      });
    }
  }
  r.seconds = seconds_since(start);
  if (r.completed()) {
    if (recorded < model.time()) model.record();
    if (state.written < model.time()) model.write_fields();
  }
  return r;
}

} // namespace mf::explicit_dynamics
