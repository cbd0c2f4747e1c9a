#include "meshfree/app/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/run_driver.hpp"
#include "meshfree/explicit/run_plan.hpp"
#include "meshfree/explicit/run_summaries.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/step.hpp"
#include <iostream>
#include <omp.h>

namespace mf::app {

explicit_dynamics::SphRunResult run_sph(const spec::ProblemSpec& spec, io::OutputDirectory* out,
                                        const distribution::Ranks& ranks, const std::string& dir,
                                        const io::Restart* restart) {
  const spec::SphSpec& s = spec.sph();
  explicit_dynamics::SphRunResult result;
  sph::Hydro h;
  {
    PhaseTimer::Scope scope(result.timer, "particles");
    h = explicit_dynamics::build_sph(s);
  }
  explicit_dynamics::require_finite_run(explicit_dynamics::planned_run(s, h), dir);
  log::info("sph: ", h.particles.size(), " particles in ", s.dimension, "D, ", s.materials.size(),
            " material(s)", s.detonation_point ? ", detonation lit" : "");
  {
    PhaseTimer::Scope scope(result.timer, "split_over_ranks");
    sph::distribute(h, ranks);
  }
  if (!ranks.serial())
    log::info("sph: spread over ", ranks.size, " MPI ranks (slabs, rebalanced at each list build)");
  explicit_dynamics::SphRun run(h, s, out, result);
  result.checkpoints = explicit_dynamics::run_to_end(run, s, result.history,
                                                     {out, dir, ranks, &spec.settings, restart});
  return result;
}

void write_sph_outputs(const spec::ProblemSpec& spec, const explicit_dynamics::SphRunResult& r,
                       io::OutputDirectory& out) {
  r.history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "sph", ""});
  summary.set_status(r.status, r.stop_reason);
  summary.set("openmp_threads", omp_get_max_threads());
  summary.set("mpi_ranks", r.mpi_ranks);
  io::Json& counts = summary.section("counts");
  io::Json& time_step = summary.section("time_step");
  explicit_dynamics::summarise(r, counts, time_step, summary.section("results"));
  // Where the stepping time goes: the neighbour search's part (outside "results", which compares
  // runs number for number).
  const double stepping = r.timer.phases().empty() ? 0.0 : r.timer.total();
  summary.section("neighbour_search")
      .set("builds", r.neighbour_rebuilds)
      .set("seconds", r.neighbour_seconds)
      .set("listed_pairs", r.neighbour_pairs)
      .set("list_bytes", r.neighbour_list_bytes)
      .set("share_of_run", stepping > 0.0 ? r.neighbour_seconds / stepping : 0.0);
  summary.section("checkpoints") = r.checkpoints.describe(stepping);
  summary.write(out, r.timer);
}

namespace {

void describe(const spec::ProblemSpec& spec) {
  explicit_dynamics::print_sph_plan(spec, std::cout);
}

double end_time(const spec::ProblemSpec& spec) {
  return spec.sph().end_time;
}

RunOutcome run(const RunRequest& q) {
  explicit_dynamics::SphRunResult r =
      run_sph(q.spec, q.out, distribution::Ranks::of(q.session.comm()), q.dir, q.restart);
  return explicit_outcome(r, q.out,
                          [&](io::OutputDirectory& out) { write_sph_outputs(q.spec, r, out); });
}

} // namespace

AnalysisEntry sph_entry() {
  return {spec::Analysis::Sph, // analysis
          "sph",               // name
          true,                // checkpoints
          true,                // folder at first file
          describe,            // describe
          nullptr,             // check
          nullptr,             // admit
          end_time,            // end time
          run};                // run
}

} // namespace mf::app
