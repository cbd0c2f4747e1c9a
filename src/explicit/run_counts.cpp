#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/sph/step.hpp"
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace mf::explicit_dynamics {

namespace {
/// A disk's sustained write rate, as the bound on checkpoint writing counts it.
constexpr double disk_bytes_per_second = 1.0e8;

/// Events at `interval` up to the end time, at most one per step.
double events(double interval, const PlannedRun& r, double steps) {
  return interval > 0.0 ? std::min(r.end_time / interval, steps) : steps;
}

/// Says which output intervals lie below the time step (after every refusal: a refused run
/// says one line).
void warn_clamped(const PlannedRun& r) {
  const std::pair<const char*, double> intervals[] = {
      {"output.history_interval", r.history_interval},
      {"output.fields_interval", r.fields_interval},
      {"output.checkpoint_interval", r.checkpoint_interval}};
  for (const auto& [key, interval] : intervals)
    if (interval > 0.0 && interval < r.dt)
      log::warn(r.key_prefix, key, ": ", interval, " s is below the time step ", r.dt,
                " s: written at every step instead");
}
} // namespace

void refuse_endless_run(const PlannedRun& r, const std::string& folder) {
  const double steps = std::ceil(r.end_time / r.dt);
  const std::string& k = r.key_prefix;
  require_run_time(k + (r.dt_key.empty() ? "time.end" : r.dt_key),
                   detail::concat(r.dt_why, r.end_time, " s in time steps of ", r.dt, " s, ",
                                  r.particles, " particles: particle-steps"),
                   steps * std::max(1.0, r.particles), r.particle_steps_per_second);
  const double frames = 2.0 + (r.fields_interval > 0.0 ? events(r.fields_interval, r, steps) : 0.0);
  require_disk(k + "output.fields_interval", "field frames", frames,
               r.particles * r.bytes_per_particle_frame, folder);
  const double rows = 1.0 + events(r.history_interval, r, steps);
  // A row is its columns written as text, about 24 characters each.
  require_disk(k + "output.history_interval", "history rows", rows, 24.0 * r.history_columns,
               folder);
  if (r.checkpoint_interval > 0.0) {
    const double n = events(r.checkpoint_interval, r, steps);
    const double seconds = n * r.particles * r.bytes_per_particle_state / disk_bytes_per_second;
    if (!(seconds <= max_run_seconds))
      fail(k, "output.checkpoint_interval: ", r.checkpoint_interval, " s: about ", n,
           " checkpoints, about ", seconds / 86400.0, " days of writing at ", disk_bytes_per_second,
           " bytes per second, more than the ", max_run_seconds / 86400.0, " days a run may take");
  }
}

void require_finite_run(const PlannedRun& r, const std::string& folder) {
  refuse_endless_run(r, folder);
  warn_clamped(r);
}

namespace {
/// A history row's columns: time, step, energies and the like, and a few per gauge.
double history_columns(std::size_t gauges) {
  return 32.0 + 8.0 * static_cast<double>(gauges);
}
} // namespace

PlannedRun planned_run(const spec::PdSpec& s, const PdSetup& setup) {
  PlannedRun r;
  r.end_time = s.end_time;
  r.dt = setup.dt;
  r.dt_key = setup.dt_key;
  r.history_interval = s.output.history_interval;
  r.fields_interval = s.output.fields_interval;
  r.checkpoint_interval = s.output.checkpoint.interval;
  r.particles = static_cast<double>(setup.particles_total);
  r.particle_steps_per_second = work_per_second::pd_particle_steps;
  r.bytes_per_particle_frame = 8.0 * 11.0; // displacement, velocity, position, damage, material
  r.bytes_per_particle_state = bytes_per::pd_particle;
  r.history_columns = history_columns(s.output.gauges.size());
  r.key_prefix = s.key_prefix;
  return r;
}

namespace {
/// A signal speed faster than light in every unit of length and time a problem may declare (the
/// speed of light is 3e14 um/s): no material makes it, so a state that gives it is wrong.
constexpr double kImpossibleSpeed = 1e15;

/// The region whose state gives particle `i` (the one that sets the first step) an impossible
/// signal speed: its key and why, so that a refusal names the pressure of 1e300 rather than the
/// end time that its time step cannot reach. None when the speed is possible or no region holds i.
void blame_region(const spec::SphSpec& s, const sph::Hydro& h, int i, PlannedRun& r) {
  if (i < 0) return;
  const particles::ParticleSet& P = h.particles;
  const double c = h.fields.c[i];
  const double v = Vec3(P.v[3 * i], P.v[3 * i + 1], P.v[3 * i + 2]).stableNorm();
  if (c + v <= kImpossibleSpeed) return; // NaN is caught where the state is checked
  const spec::Point x = P.position(i);
  for (const spec::SphRegion& g : s.regions)
    if (P.material[i] == g.material && g.region.contains(x, 1e-9 * g.spacing)) {
      const bool moving = v > c;
      r.dt_key = g.key_path + "." + (moving ? "velocity" : g.state_key);
      r.dt_why = detail::concat("it gives its particles a ", moving ? "speed" : "sound speed",
                                " of ", moving ? v : c, ", faster than light: ");
      return;
    }
}
} // namespace

PlannedRun planned_run(const spec::SphSpec& s, const sph::Hydro& h) {
  PlannedRun r;
  int limiting = -1;
  const double particles = h.particles.size();
  r.end_time = s.end_time;
  r.dt = sph::stable_step(h, &limiting);
  blame_region(s, h, limiting, r);
  r.history_interval = s.output.history_interval;
  r.fields_interval = s.output.fields_interval;
  r.checkpoint_interval = s.output.checkpoint.interval;
  r.particles = particles;
  r.particle_steps_per_second = work_per_second::sph_particle_steps;
  r.bytes_per_particle_frame = 8.0 * 24.0; // 24 values: motion, state, stress, position
  r.bytes_per_particle_state = bytes_per::sph_particle(s.dimension);
  r.history_columns = history_columns(s.output.gauges.size());
  r.key_prefix = s.key_prefix;
  return r;
}

} // namespace mf::explicit_dynamics
