#pragma once
// What summary.json says of an explicit run (counts, time step, results), for a run of its own or
// for the explicit stage of a staged run.
#include "meshfree/explicit/pd_run.hpp"
#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/io/results.hpp"

namespace mf::explicit_dynamics {

/// Sections counts, time_step and results of `out` (a summary's sections or a stage's).
void summarise(const SphRunResult& r, io::Json& counts, io::Json& time_step, io::Json& results);
void summarise(const PdRunResult& r, io::Json& counts, io::Json& time_step, io::Json& results);

} // namespace mf::explicit_dynamics
