#include "meshfree/app/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/explicit/time_loop.hpp"

namespace mf::app {

explicit_dynamics::SphRunResult run_sph(const io::ProblemSpec& spec, io::OutputDirectory* out) {
  const io::SphSpec& s = *spec.sph;
  explicit_dynamics::SphRunResult result;
  sph::Hydro h;
  {
    PhaseTimer::Scope scope(result.timer, "particles");
    h = explicit_dynamics::build_sph(s);
  }
  log::info("sph: ", h.particles.size(), " particles in ", s.dimension, "D, ", s.materials.size(),
            " material(s)", s.detonation_point ? ", detonation lit" : "");
  explicit_dynamics::SphRun run(h, s, out, result);
  run.finish(
      explicit_dynamics::run_time_loop(run, {s.end_time, s.history_interval, s.fields_interval}));
  return result;
}

void write_sph_outputs(const io::ProblemSpec& spec, const explicit_dynamics::SphRunResult& r,
                       io::OutputDirectory& out) {
  r.history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "sph", ""});
  summary.set_status(r.status, r.stop_reason);
  summary.section("counts")
      .set("particles", r.particles)
      .set("steps", r.steps)
      .set("neighbour_list_builds", r.neighbour_rebuilds);
  summary.section("time_step")
      .set("first", r.first_dt)
      .set("smallest", r.smallest_dt)
      .set("limited_by", r.dt_limit);
  io::Json gauges;
  for (const auto& [name, value] : r.gauge_maxima) gauges.set(name, value);
  summary.section("results")
      .set("peak_pressure", r.peak_pressure)
      .set("energy_error_relative", r.energy_error)
      .set("particle_steps_per_second", r.particle_steps_per_second)
      .set("gauge_maxima", gauges);
  summary.write(out, r.timer);
}

} // namespace mf::app
