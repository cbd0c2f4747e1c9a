#pragma once
// Explicit bond-based peridynamics run from a problem file: the body from the spec, velocity-Verlet
// steps to the end time, histories and fields.
#include "meshfree/io/output.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/pd/run.hpp"

namespace mf::app {

/// Runs the problem to its end time; fields go to `out` (null: none).
pd::RunResult run_peridynamics(const io::ProblemSpec& spec, io::OutputDirectory* out);

/// history.csv and summary.json.
void write_pd_outputs(const io::ProblemSpec& spec, const pd::RunResult& r,
                      io::OutputDirectory& out);

} // namespace mf::app
