#pragma once
// Checkpoints of a run that goes step by step (DIR/checkpoint/): the whole state at one instant,
// from which `meshfree run FILE --restart DIR` goes on as the run would have, bit for bit with the
// same numbers of ranks and threads. An explicit run writes one every output.checkpoint_interval
// of simulated time and every output.checkpoint_wall_interval seconds of wall time (600 by
// default), at the end of a step; an elastoplastic run counts converged increments instead
// (output.checkpoint_every).
//
// Layout: each rank writes its state into state-<g>.<rank>.h5 (io/state_file.hpp); once every
// rank has, rank 0 names generation g in checkpoint.txt (a new file renamed over the old one, so
// the name always points at a whole checkpoint) and removes generation g - 1. The field steps
// written up to a checkpoint are closed into <stem>.part-<k>.h5 beside them (io/output.hpp,
// FieldSeries::split), so that a killed run's fields survive whole; the run that completes
// merges them into DIR/fields.h5 and removes the folder.
//
// A checkpoint knows its run: every rank's file carries the layout (meta.format), the problem's
// identity (a hash of the settings a restart may not change), the ranks, the time and the step;
// the state carries the counts of particles, nodes or points, and every array its checksum
// (io/state_file.hpp). A restart checks all of them before it writes anything, and refuses what
// differs (CheckpointRefused, exit 2). Nothing under DIR/checkpoint is read or written through a
// link.
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/state_file.hpp"
#include "meshfree/spec/region_spec.hpp"
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mf::io {

/// The keys a restart may change: the end time, the output intervals and checkpoint_every.
bool restart_may_change(const std::string& key);

/// The checkpoint a restart starts from (find_restart).
struct Restart {
  std::string folder;
  long generation = 0;
  int ranks = 1;
  int threads = 1;
  double time = 0.0;
  long step = 0;
  /// This rank's state file.
  std::unique_ptr<StateReader> open(int rank) const;
  /// Reads every rank's file through and checks each array against its checksum.
  void verify() const;
};

/// The instant a state read back from `file` holds must be the one its header gave.
void check_resumed(const StateReader& file, double time, long step);

/// A refusal found while this rank read its state back: over several MPI ranks the others may
/// have found none and wait for this one in a collective call, so every rank stops here (exit
/// 2, the line said by this rank). On one rank it returns, and the refusal goes on up.
void refused_on_this_rank(const CheckpointRefused& refusal);

/// The last checkpoint in DIR/checkpoint, checked against the problem as given now (`settings`,
/// on `ranks` MPI ranks, ending at `end_time`): another layout, a different number of ranks, a
/// key that changed other than those a restart may change (the problem's identity), a time that
/// is not finite or not inside the run, or no checkpoint at all is an input error naming it
/// (CheckpointRefused, or Error for a missing one). DIR/checkpoint and its files are read only
/// as what they are, never through a link.
Restart find_restart(const std::string& dir, const spec::ProblemSettings& settings, int ranks,
                     double end_time);

/// What a run's checkpoints cost (summary.json's "checkpoints").
struct CheckpointCounts {
  int written = 0;
  double seconds = 0.0;       // writing them
  double bytes = 0.0;         // of the last one, over every rank
  double restarted_at = -1.0; // the instant the run restarted from, or < 0
  /// The counts and their share of a run of `run_seconds`.
  Json describe(double run_seconds) const;
};

/// Removes DIR/checkpoint (a run into DIR completed, and its results supersede the checkpoint):
/// the files meshfree writes there and no others; nothing while another run holds the folder.
void remove_checkpoints(const std::string& dir);

/// The checkpoints a run writes into DIR/checkpoint (every rank holds one; collective calls).
class Checkpoints {
public:
  /// `restart`: the checkpoint this run started from (its generation is continued), or null. An
  /// empty `dir` or a policy without intervals writes none.
  Checkpoints(std::string dir, const distribution::Ranks& ranks, spec::CheckpointPolicy policy,
              spec::ProblemSettings settings, const Restart* restart = nullptr);
  ~Checkpoints();
  Checkpoints(const Checkpoints&) = delete;
  Checkpoints& operator=(const Checkpoints&) = delete;
  /// True when one is due at the end of a step reaching simulated time t (collective on the wall
  /// clock: rank 0's decides).
  bool due(double t);
  /// Writes one at (t, step): save() fills this rank's file. Collective. The first one takes the
  /// folder's lock (`checkpoint/.lock`, flock): while another run into DIR holds it, this run
  /// says so and writes none.
  void write(double t, long step, const std::function<void(StateWriter&)>& save);
  /// Where part k of a field series of this name is kept.
  std::string part(const std::string& stem, int k) const;
  CheckpointCounts counts() const { return {written_, seconds_, bytes_, restarted_at_}; }
  /// The checkpoint being written (in write's save()), or the last one.
  long generation() const { return generation_; }

private:
  std::string dir_, folder_;
  distribution::Ranks ranks_;
  spec::CheckpointPolicy policy_;
  spec::ProblemSettings settings_;
  long generation_ = 0;
  int lock_ = -1; // the folder's lock file, held while this run writes there
  bool locked_ = false;
  bool cleared_ = false; // an earlier run's checkpoint was removed (or continued)
  double next_time_ = 0.0;
  std::chrono::steady_clock::time_point last_;
  int written_ = 0;
  double seconds_ = 0.0, bytes_ = 0.0; // writing them; the last one over every rank
  double restarted_at_ = -1.0;
};

} // namespace mf::io
