#pragma once
// A staged run (analysis: staged): an implicit preload whose state starts an explicit stage
// (stages/staged_run.hpp), as an entry of the table of analyses.
#include "meshfree/app/analysis.hpp"

namespace mf::app {

/// The table entry of `analysis: staged`.
AnalysisEntry staged_entry();

} // namespace mf::app
