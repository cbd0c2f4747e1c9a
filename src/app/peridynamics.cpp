#include "meshfree/app/peridynamics.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/run_summaries.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include <omp.h>

namespace mf::app {

explicit_dynamics::PdRunResult run_peridynamics(const io::ProblemSpec& spec,
                                                io::OutputDirectory* out,
                                                const distribution::Ranks& ranks,
                                                const std::string& dir,
                                                const io::Restart* restart) {
  const io::PdSpec& s = *spec.pd;
  explicit_dynamics::PdRunResult result;
  explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(spec, result.timer, ranks);
  explicit_dynamics::require_finite_run(explicit_dynamics::planned_run(s, setup), dir);
  explicit_dynamics::log_pd_setup(spec, setup);
  result.mpi_ranks = ranks.size;
  explicit_dynamics::PdRun run(setup, s, out, result);
  // history.csv grows on disk as the run goes: a run that is killed keeps it up to then.
  if (out) result.history.stream_to(*out);
  io::Checkpoints checkpoints(dir, ranks, s.checkpoint, spec.settings, restart);
  const auto resume = restart ? restart->open(ranks.rank) : nullptr;
  run.finish(explicit_dynamics::run_time_loop(
      run, {s.end_time, s.history_interval, s.fields_interval}, &checkpoints, resume.get()));
  result.checkpoints = checkpoints.counts();
  return result;
}

void write_pd_outputs(const io::ProblemSpec& spec, const explicit_dynamics::PdRunResult& r,
                      io::OutputDirectory& out) {
  r.history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "peridynamics", ""});
  summary.set_status(r.status, r.stop_reason);
  summary.set("openmp_threads", omp_get_max_threads());
  summary.set("mpi_ranks", r.mpi_ranks);
  io::Json& counts = summary.section("counts");
  io::Json& time_step = summary.section("time_step");
  explicit_dynamics::summarise(r, counts, time_step, summary.section("results"));
  summary.section("checkpoints") = r.checkpoints.describe(r.timer.total());
  if (r.relaxation)
    summary.section("relaxation")
        .set("iterations", r.relaxation->iterations)
        .set("residual_ratio", r.relaxation->residual_ratio)
        .set("seconds", r.relaxation->seconds);
  summary.write(out, r.timer);
}

} // namespace mf::app
