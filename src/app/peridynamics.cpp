#include "meshfree/app/peridynamics.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/run_driver.hpp"
#include "meshfree/explicit/run_plan.hpp"
#include "meshfree/explicit/run_summaries.hpp"
#include <iostream>
#include <omp.h>

namespace mf::app {

explicit_dynamics::PdRunResult run_peridynamics(const spec::ProblemSpec& spec,
                                                io::OutputDirectory* out,
                                                const distribution::Ranks& ranks,
                                                const std::string& dir,
                                                const io::Restart* restart) {
  const spec::PdSpec& s = spec.pd();
  explicit_dynamics::PdRunResult result;
  explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(spec, result.timer, ranks);
  explicit_dynamics::require_finite_run(explicit_dynamics::planned_run(s, setup), dir);
  explicit_dynamics::log_pd_setup(spec, setup);
  result.mpi_ranks = ranks.size;
  explicit_dynamics::PdRun run(setup, s, out, result);
  result.checkpoints = explicit_dynamics::run_to_end(run, s, result.history,
                                                     {out, dir, ranks, &spec.settings, restart});
  return result;
}

void write_pd_outputs(const spec::ProblemSpec& spec, const explicit_dynamics::PdRunResult& r,
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

namespace {

void describe(const spec::ProblemSpec& spec) {
  explicit_dynamics::print_pd_plan(spec, std::cout);
}

double end_time(const spec::ProblemSpec& spec) {
  return spec.pd().end_time;
}

RunOutcome run(const RunRequest& q) {
  explicit_dynamics::PdRunResult r =
      run_peridynamics(q.spec, q.out, distribution::Ranks::of(q.session.comm()), q.dir, q.restart);
  return explicit_outcome(r, q.out,
                          [&](io::OutputDirectory& out) { write_pd_outputs(q.spec, r, out); });
}

} // namespace

AnalysisEntry peridynamics_entry() {
  return {spec::Analysis::Peridynamics, // analysis
          "peridynamics",               // name
          true,                         // checkpoints
          true,                         // folder at first file
          describe,                     // describe
          nullptr,                      // check
          nullptr,                      // admit
          end_time,                     // end time
          run};                         // run
}

} // namespace mf::app
