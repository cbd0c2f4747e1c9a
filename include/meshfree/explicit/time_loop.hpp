#pragma once
// The time loop of every explicit analysis (peridynamics, SPH): steps to the end time, a history
// row every history_interval, fields every fields_interval and at the end, a progress line every
// tenth of the run with an estimate of the time left, and a stop naming the step, time, particle
// and position when the state stops being finite. The model is a template argument, so its
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
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/core/types.hpp"
#include <chrono>
#include <cmath>
#include <string>

namespace mf::explicit_dynamics {

struct Schedule {
  double end_time = 0.0;
  double history_interval = 0.0; // <= 0: every step
  double fields_interval = 0.0;  // <= 0: at the start and the end only
};

struct LoopReport {
  long steps = 0;
  double seconds = 0.0;         // wall time of the loop
  double advance_seconds = 0.0; // of which in the model's advance()
  std::string status = "completed", stop_reason;
  bool completed() const { return status == "completed"; }
};

template <class Model> LoopReport run_time_loop(Model& model, const Schedule& s) {
  using Clock = std::chrono::steady_clock;
  LoopReport r;
  const auto stop = [&r](std::string reason) {
    r.status = "failed";
    r.stop_reason = std::move(reason);
  };
  model.track();
  model.record();
  model.write_fields();
  double recorded = model.time();
  double next_history = s.history_interval, next_fields = s.fields_interval;
  double next_progress = 0.1 * s.end_time;
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
      while (s.history_interval > 0.0 && next_history <= model.time() * (1 + 1e-12))
        next_history += s.history_interval;
    }
    if (s.fields_interval > 0.0 && model.time() >= next_fields * (1 - 1e-12)) {
      model.write_fields();
      while (next_fields <= model.time() * (1 + 1e-12)) next_fields += s.fields_interval;
    }
    if (model.time() >= next_progress) {
      const double elapsed = seconds_since(start);
      const double left = elapsed * (s.end_time - model.time()) / model.time();
      log::info("  t = ", model.time(), " (",
                static_cast<int>(std::lround(100 * model.time() / s.end_time)), "%), step ",
                model.step(), ", ", model.progress(), ", ", elapsed, " s, about ", left, " s left");
      next_progress += 0.1 * s.end_time;
    }
  }
  r.seconds = seconds_since(start);
  if (r.completed()) {
    if (recorded < model.time()) model.record();
    model.write_fields();
  }
  return r;
}

} // namespace mf::explicit_dynamics
