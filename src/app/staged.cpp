#include "meshfree/app/staged.hpp"
#include "meshfree/explicit/run_plan.hpp"
#include "meshfree/stages/staged_run.hpp"
#include <iostream>
#include <limits>

namespace mf::app {

namespace {

/// Each stage as its own analysis describes itself, with where it starts from.
void describe_stages(const spec::ProblemSpec& spec) {
  for (std::size_t k = 0; k < spec.staged().stages.size(); ++k) {
    const spec::StageLink& l = spec.staged().links[k];
    std::cout << "stage " << spec.staged().stages[k].stage;
    if (l.from >= 0)
      std::cout << " from " << spec.staged().stages[l.from].stage << " (" << l.hold.size()
                << " condition(s) held, " << l.release.size() << " released)";
    std::cout << ":\n";
    entry_of(spec.staged().stages[k].analysis).describe(spec.staged().stages[k]);
  }
}

/// The explicit stages bounded as `check` bounds them (their particles and first step built as
/// their set-up builds them), before the preload runs: a stage that would never end is refused
/// as input, with its key path (stages[1].time.end), not after the preload's solve.
void admit(const spec::ProblemSpec& spec, const std::string& folder) {
  for (const spec::ProblemSpec& stage : spec.staged().stages) {
    if (stage.is_sph()) explicit_dynamics::require_finite_sph_run(stage, folder);
    if (stage.is_pd()) explicit_dynamics::require_finite_pd_run(stage, folder);
  }
}

/// Checkpoints are the explicit stage's.
double end_time(const spec::ProblemSpec& spec) {
  const spec::ProblemSpec& stage = spec.staged().stages.at(1);
  const AnalysisEntry& e = entry_of(stage.analysis);
  return e.end_time ? e.end_time(stage) : std::numeric_limits<double>::infinity();
}

RunOutcome run(const RunRequest& q) {
  const auto r = stages::run_staged(q.spec, q.session, q.out, q.dir, q.restart);
  return {r.exit_code, r.stop_reason};
}

} // namespace

AnalysisEntry staged_entry() {
  return {spec::Analysis::Staged, // analysis
          "staged",               // name
          true,                   // checkpoints
          false,                  // folder at first file
          describe_stages,        // describe
          nullptr,                // check
          admit,                  // admit
          end_time,               // end time
          run};                   // run
}

} // namespace mf::app
