#pragma once
// What an explicit run will do, counted before it starts (steps, field frames, history rows,
// checkpoints) and bounded by the machine: `meshfree check` and `run` refuse the same runs, with
// the key that asked for them, before anything is written.
#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/spec/sph_spec.hpp"
#include "meshfree/sph/hydro.hpp"
#include <string>

namespace mf::explicit_dynamics {

struct PlannedRun {
  double end_time = 0.0;
  double dt = 0.0;    // the first time step
  std::string dt_key; // the key whose value set it, when not the stability bound
  std::string dt_why; // what about that value set it (SPH: a region's signal speed)
  double history_interval = 0.0, fields_interval = 0.0, checkpoint_interval = 0.0;
  double particles = 0.0;
  double particle_steps_per_second = 0.0; // per core (core/run_bounds.hpp)
  double bytes_per_particle_frame = 0.0;  // the fields one frame writes per particle
  double bytes_per_particle_state = 0.0;  // what a checkpoint writes per particle
  double history_columns = 0.0;
  std::string key_prefix; // the stage's path in a staged run ("stages[1]."), before every key
};

/// Refuses a run whose steps would take longer than max_run_seconds on the cores here, or whose
/// frames or history rows would not fit on the disk of `folder`, or whose checkpoints would take
/// that long to write.
void refuse_endless_run(const PlannedRun& r, const std::string& folder);
/// refuse_endless_run, then a warning for each output interval below the time step, clamped: the
/// loop writes at most once per step, and an SPH step changes as the run goes, so an interval
/// below the first step says "every step" rather than something impossible.
void require_finite_run(const PlannedRun& r, const std::string& folder);

/// The run a peridynamic set-up and its spec make.
PlannedRun planned_run(const spec::PdSpec& s, const PdSetup& setup);
/// The run an SPH spec makes with the body `h` it built: its first stable step, and the region
/// whose state sets it when that state's signal speed is beyond any physical one.
PlannedRun planned_run(const spec::SphSpec& s, const sph::Hydro& h);

} // namespace mf::explicit_dynamics
