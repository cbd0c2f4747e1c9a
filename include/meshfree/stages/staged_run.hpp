#pragma once
// A staged run (analysis: staged): the implicit preload, then the explicit stage that starts from
// its state, into one output: the preload's own files with its name as prefix
// (<stage>_fields.h5, <stage>_gauss_points.h5, <stage>_history.csv, <stage>_summary.json), one
// history.csv and one fields.h5/.xmf series on the particles for the whole run (the preload at
// pseudo-times -1..0, the event from t = 0, a "stage" column), and one summary.json with a
// section per stage and a "transfer" section.
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::stages {

struct StagedOutcome {
  std::string status = "completed", stop_reason;
  int exit_code = 0; // 0 completed, 1 the explicit stage failed, 3 the preload did not converge
};

/// Runs every stage; results go to `out` (rank 0; null: none). The explicit stage writes
/// checkpoints into `dir`/checkpoint (empty: none); with `restart` the preload runs again and the
/// explicit stage goes on from that checkpoint.
StagedOutcome run_staged(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                         io::OutputDirectory* out, const std::string& dir = {},
                         const io::Restart* restart = nullptr);

} // namespace mf::stages
