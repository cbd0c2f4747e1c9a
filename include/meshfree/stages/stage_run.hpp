#pragma once
// The steps the SPH and the peridynamic stage share around their own transfer: the preload
// replayed on the stage's particles, then the run from t = 0 to the stage's end with the stage's
// history (explicit_dynamics::run_to_end), and what the stage reports of it.
#include "meshfree/explicit/run_driver.hpp"
#include "meshfree/explicit/run_summaries.hpp"
#include "meshfree/stages/explicit_stage.hpp"

namespace mf::stages {

/// The preload's increments replayed on the run's particles (put(k) puts increment k at its
/// pseudo-time), each recorded in the history and written as a field step, except the last
/// one, which is recorded (at t = 0, as the preload's end) but not written: the run's first
/// field step is the same instant.
template <class Run, class Put> void replay_preload(Run& run, int increments, Put put) {
  const int N = increments - 1;
  for (int k = 0; k <= N; ++k) {
    put(k);
    run.record();
    if (k < N) run.write_fields();
  }
}

/// After the replay: the stage's history (the replay's rows, then the run's as they come), the
/// transferred state put back for t = 0 (`restore`), the run to the end of `s`, and its counts,
/// results, checkpoints, status and timer in `st`.
template <class Run, class Result, class Spec, class Restore>
void run_stage(ExplicitStage& st, Run& run, Result& result, const Spec& s,
               const spec::StageLink& link, int index, const explicit_dynamics::RunPlace& place,
               Restore restore) {
  const io::History replay = take_rows(result.history);
  begin_stage_history(st, replay, result.history, s.output.gauges, link.from, index);
  restore();
  st.checkpoints = explicit_dynamics::run_to_end(run, s, st.history, place);
  explicit_dynamics::summarise(result, st.counts, st.time_step, st.results);
  record_stage(st, result.status, result.stop_reason, result.timer);
}

} // namespace mf::stages
