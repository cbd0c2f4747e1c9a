#pragma once
// What an adapted run writes of its refinement: results.adaptivity in summary.json, adapt.csv
// (a row per pilot pass, or per estimate between increments, and one for the final state:
// nodes, estimate, nodes marked, the increment after which it was made) and
// error_indicator.h5/.xmf (eta_I and the spacing at every node of the last cloud, for ParaView).
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/results.hpp"

namespace mf::implicit {

/// results.adaptivity: the target, why refinement ended, the passes and the final estimate.
io::Json adaptation_json(const spec::ProblemSpec& spec, const Adaptation& a,
                         const ErrorEstimate& final_estimate);

/// adapt.csv, adapted_refinement.yaml (the last cloud's boxes) and the error_indicator series
/// (rank 0); `increments` is the analysis' count of converged increments (0 for an elastic one).
void write_adaptation(const spec::ProblemSpec& spec, const Adaptation& a,
                      const ErrorEstimate& final_estimate, long increments,
                      io::OutputDirectory& out);

} // namespace mf::implicit
