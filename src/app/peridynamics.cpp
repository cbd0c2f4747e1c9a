#include "meshfree/app/peridynamics.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include <omp.h>

namespace mf::app {

explicit_dynamics::PdRunResult run_peridynamics(const io::ProblemSpec& spec,
                                                io::OutputDirectory* out) {
  const io::PdSpec& s = *spec.pd;
  explicit_dynamics::PdRunResult result;
  explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(spec, result.timer);
  explicit_dynamics::log_pd_setup(spec, setup);
  explicit_dynamics::PdRun run(setup, s, out, result);
  run.finish(
      explicit_dynamics::run_time_loop(run, {s.end_time, s.history_interval, s.fields_interval}));
  return result;
}

void write_pd_outputs(const io::ProblemSpec& spec, const explicit_dynamics::PdRunResult& r,
                      io::OutputDirectory& out) {
  r.history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "peridynamics", ""});
  summary.set_status(r.status, r.stop_reason);
  summary.set("openmp_threads", omp_get_max_threads());
  summary.section("counts")
      .set("particles", r.particles)
      .set("bonds", r.bonds)
      .set("steps", r.steps);
  summary.section("time_step").set("dt", r.dt).set("limited_by", r.dt_limit);
  if (r.relaxation)
    summary.section("relaxation")
        .set("iterations", r.relaxation->iterations)
        .set("residual_ratio", r.relaxation->residual_ratio)
        .set("seconds", r.relaxation->seconds);
  io::Json& results = summary.section("results");
  results.set("broken_bonds", r.broken_bonds)
      .set("max_damage", r.max_damage)
      .set("energy_balance_relative", r.energy_drift)
      .set("bond_evaluations_per_second", r.bond_updates_per_second);
  // Largest magnitudes of every recorded history column (gauges, impactor, crack).
  io::Json maxima;
  for (std::size_t c = 2; c < r.history.columns().size(); ++c)
    maxima.set(r.history.columns()[c], r.history.max_abs(c));
  results.set("max_abs", maxima);
  io::Json gauges;
  for (const auto& [name, v] : r.gauge_maxima) gauges.set(name, v);
  results.set("gauge_max_abs_every_step", gauges);
  summary.write(out, r.timer);
}

} // namespace mf::app
