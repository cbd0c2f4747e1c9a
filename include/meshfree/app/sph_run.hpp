#pragma once
// An SPH run from a problem file (analysis: sph): particles from the regions, lighting times from
// the detonation point, CFL-limited steps to the end time, histories, gauges and fields.
#include "meshfree/app/analysis.hpp"
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::app {

/// Runs the problem to its end time spread over `ranks`; fields go to `out` (null: none; the
/// ranks other than the first have none). Collective. Checkpoints go to `dir`/checkpoint (empty:
/// none); with `restart` the run goes on from that checkpoint.
explicit_dynamics::SphRunResult run_sph(const spec::ProblemSpec& spec, io::OutputDirectory* out,
                                        const distribution::Ranks& ranks = {},
                                        const std::string& dir = {},
                                        const io::Restart* restart = nullptr);

/// history.csv and summary.json.
void write_sph_outputs(const spec::ProblemSpec& spec, const explicit_dynamics::SphRunResult& r,
                       io::OutputDirectory& out);

/// The table entry of `analysis: sph`.
AnalysisEntry sph_entry();

} // namespace mf::app
