#pragma once
// The table of analyses: what `meshfree check` and `meshfree run` do for each `analysis:` of a
// problem file, looked up once. A new analysis is a reader in io/ (io/analysis_read.hpp), a file
// in app/ with its entry, and one row of the table in app/analysis.cpp.
#include "meshfree/core/timer.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <string>

namespace mf::app {

/// What `meshfree run` hands an analysis once the problem, the output folder and any checkpoint
/// were accepted.
struct RunRequest {
  const spec::ProblemSpec& spec;
  const solvers::PetscSession& session;
  io::OutputDirectory* out;   // rank 0's output folder; null on the other ranks
  const std::string& dir;     // the folder's path (checkpoints go to dir/checkpoint)
  const io::Restart* restart; // the checkpoint to go on from, or null
};

/// How a run ended: 0 completed, 1 failed (`reason` says why), 3 stopped (an implicit schedule
/// that did not converge; its summary says where).
struct RunOutcome {
  int exit_code = 0;
  std::string reason;
};

struct AnalysisEntry {
  spec::Analysis analysis;
  const char* name; // as in the problem file
  /// Goes step by step and writes checkpoints that --restart continues.
  bool checkpoints = false;
  /// Its set-up is input checking too: the output folder is made at the first file written, and
  /// an error before that is refused as input with nothing written.
  bool folder_at_first_file = false;
  /// Prints what a run would build (counts, time step, memory) as one stage of a staged run;
  /// throws what the run's set-up would throw.
  void (*describe)(const spec::ProblemSpec& spec) = nullptr;
  /// `meshfree check`, where it does more than `describe` (the bounds a run of its own checks
  /// before it writes); null: `describe`.
  void (*check)(const spec::ProblemSpec& spec) = nullptr;
  /// What a run refuses as input before anything is written into `folder` (rank 0): a mesh that
  /// cannot be read, a run that would never end or not fit on the disk. May be null.
  void (*admit)(const spec::ProblemSpec& spec, const std::string& folder) = nullptr;
  /// The last instant a checkpoint of this run may hold (infinity when checkpoints count
  /// increments). May be null when `checkpoints` is false.
  double (*end_time)(const spec::ProblemSpec& spec) = nullptr;
  /// Runs the analysis and writes its results.
  RunOutcome (*run)(const RunRequest& request) = nullptr;
};

/// The entry of `analysis`.
const AnalysisEntry& entry_of(spec::Analysis analysis);

/// One info line with the wall time of each phase of `timer`.
void log_phases(const PhaseTimer& timer);

/// A run's result `r` written by `write(out)` (rank 0's folder; null on the other ranks) in the
/// phase "output", and its phases logged.
template <class Result, class Write>
void write_and_log(Result& r, io::OutputDirectory* out, Write write) {
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) write(*out);
  }
  log_phases(r.timer);
}

/// An explicit run's result `r` written by `write(out)` (rank 0) and its phases logged: a failed
/// run is exit 1 with its reason.
template <class Result, class Write>
RunOutcome explicit_outcome(Result& r, io::OutputDirectory* out, Write write) {
  write_and_log(r, out, write);
  return {r.status == "failed" ? 1 : 0, r.stop_reason};
}

/// The names of the analyses whose runs write checkpoints, as a sentence ("a, b and c").
std::string checkpointing_analyses();

} // namespace mf::app
