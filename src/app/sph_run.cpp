#include "meshfree/app/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/run_summaries.hpp"
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
  io::Json& counts = summary.section("counts");
  io::Json& time_step = summary.section("time_step");
  explicit_dynamics::summarise(r, counts, time_step, summary.section("results"));
  summary.write(out, r.timer);
}

} // namespace mf::app
