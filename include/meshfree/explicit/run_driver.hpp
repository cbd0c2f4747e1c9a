#pragma once
// The end of every explicit run, standalone (app/peridynamics, app/sph_run) or the explicit stage
// of a staged run (stages/pd_stage, stages/sph_stage), once: the history streamed to
// history.csv, the checkpoints of the spec's policy, the state a restart resumes from, the time
// loop to the spec's end time, the run's finish, and what its checkpoints cost.
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/io/results.hpp"
#include <string>

namespace mf::explicit_dynamics {

/// Where an explicit run writes, over which ranks, and what it restarts from.
struct RunPlace {
  io::OutputDirectory* out = nullptr;              // fields and history.csv (null: none)
  std::string dir;                                 // the output folder ("": no checkpoints)
  distribution::Ranks ranks;                       // the MPI ranks the body is spread over
  const spec::ProblemSettings* settings = nullptr; // the problem as given (a restart matches it)
  const io::Restart* restart = nullptr;            // the checkpoint the run goes on from, or null
};

/// The loop's schedule in a spec (spec::PdSpec, spec::SphSpec): end time and output intervals.
template <class Spec> Schedule schedule_of(const Spec& s) {
  return {s.end_time, s.output.history_interval, s.output.fields_interval};
}

/// Runs `run` (PdRun, SphRun: time_loop.hpp's model with finish(LoopReport)) from where it
/// stands, or from `place.restart`, to the end time of `s`, and finishes it; `history` (the rows
/// recorded so far and every row to come) goes to `place.out`'s history.csv as it grows, so that
/// a run that is killed keeps it up to then. Returns what the checkpoints written on the way
/// cost.
template <class Run, class Spec>
io::CheckpointCounts run_to_end(Run& run, const Spec& s, io::History& history,
                                const RunPlace& place) {
  if (place.out) history.stream_to(*place.out);
  io::Checkpoints checkpoints(place.dir, place.ranks, s.output.checkpoint,
                              place.settings ? *place.settings : spec::ProblemSettings{},
                              place.restart);
  const auto resume = place.restart ? place.restart->open(place.ranks.rank) : nullptr;
  run.finish(run_time_loop(run, schedule_of(s), &checkpoints, resume.get()));
  return checkpoints.counts();
}

} // namespace mf::explicit_dynamics
