#include "meshfree/explicit/run_summaries.hpp"

namespace mf::explicit_dynamics {

void summarise(const SphRunResult& r, io::Json& counts, io::Json& time_step, io::Json& results) {
  counts.set("particles", r.particles)
      .set("steps", r.steps)
      .set("neighbour_list_builds", r.neighbour_rebuilds);
  // Particle-steps whose smoothing length was held at its bound (discretisation.smoothing_bounds).
  io::Json held;
  held.set("at_min", r.bounded_h.at_min).set("at_max", r.bounded_h.at_max);
  counts.set("smoothing_length_held", held);
  if (r.mpi_ranks > 1)
    counts.set("ghost_particles", r.remote_ghosts)
        .set("ghost_particles_largest_rank", r.remote_ghosts_largest)
        .set("migrated_particles", r.migrated);
  time_step.set("first", r.first_dt).set("smallest", r.smallest_dt).set("limited_by", r.dt_limit);
  // peak_pressure is the signed largest pressure of any particle (compression positive); a
  // gauge's values are magnitudes (|p|, speed), under the key peridynamics uses.
  io::Json gauges;
  for (const auto& [name, value] : r.gauge_maxima) gauges.set(name, value);
  results.set("peak_pressure", r.peak_pressure)
      .set("energy_error_relative", r.energy_error)
      .set("particle_steps_per_second", r.particle_steps_per_second)
      .set("gauge_max_abs_every_step", gauges);
}

void summarise(const PdRunResult& r, io::Json& counts, io::Json& time_step, io::Json& results) {
  counts.set("particles", r.particles).set("bonds", r.bonds).set("steps", r.steps);
  if (r.mpi_ranks > 1)
    counts.set("ghost_particles", r.ghosts).set("ghost_particles_largest_rank", r.ghosts_largest);
  time_step.set("dt", r.dt).set("limited_by", r.dt_limit);
  results.set("broken_bonds", r.broken_bonds)
      .set("max_damage", r.max_damage)
      .set("energy_balance_relative", r.energy_drift)
      .set("bond_evaluations_per_second", r.bond_updates_per_second);
  io::Json bytes;
  bytes.set("steady", r.bond_bytes_steady).set("peak", r.bond_bytes_peak);
  results.set("bond_bytes_per_bond", bytes);
  // Largest magnitudes of every recorded history column (gauges, impactor, crack), from the
  // third column on (the first two are time and step).
  io::Json maxima;
  for (std::size_t c = 2; c < r.history.columns().size(); ++c)
    maxima.set(r.history.columns()[c], r.history.max_abs(c));
  results.set("max_abs", maxima);
  io::Json gauges;
  for (const auto& [name, v] : r.gauge_maxima) gauges.set(name, v);
  results.set("gauge_max_abs_every_step", gauges);
}

} // namespace mf::explicit_dynamics
