#pragma once
// Explicit bond-based peridynamics run from a problem file: the body from the spec, velocity-Verlet
// steps to the end time, histories and fields.
#include "meshfree/app/analysis.hpp"
#include "meshfree/explicit/pd_run.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::app {

/// Runs the problem to its end time, spread over `ranks`; fields go to `out` (null: none; on
/// rank 0 only when there are several). Checkpoints go to `dir`/checkpoint (empty: none); with
/// `restart` the run goes on from that checkpoint.
explicit_dynamics::PdRunResult run_peridynamics(const spec::ProblemSpec& spec,
                                                io::OutputDirectory* out,
                                                const distribution::Ranks& ranks = {},
                                                const std::string& dir = {},
                                                const io::Restart* restart = nullptr);

/// history.csv and summary.json.
void write_pd_outputs(const spec::ProblemSpec& spec, const explicit_dynamics::PdRunResult& r,
                      io::OutputDirectory& out);

/// The table entry of `analysis: peridynamics`.
AnalysisEntry peridynamics_entry();

} // namespace mf::app
