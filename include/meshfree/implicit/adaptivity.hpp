#pragma once
// Error-driven refinement of a plane meshfree body's nodes (discretisation.adapt): pilot solves
// on the cloud, the recovery estimate of each (implicit/error_indicator), Doerfler's marking
// ([Doerfler 1996]) of the nodes that carry the bulk of the estimated error, and boxes of half
// their spacing around them (geometry::Refinement, so that node generation, supports and
// background cells follow as they follow a problem's own refinement boxes). The analysis then
// runs once on the last cloud.
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/error_indicator.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace mf::implicit {

/// One pilot solve: its cloud's node count, the estimate, the nodes marked after it.
struct AdaptPass {
  int nodes = 0;
  double estimate = 0.0; // relative, ErrorEstimate::relative
  int marked = 0;
  double seconds = 0.0;
  int increment = 0; // refined during the analysis: after this increment (0: a pilot)
};

struct Adaptation {
  std::vector<AdaptPass> passes;
  std::vector<geometry::Refinement> refinement; // the last cloud's boxes, the problem's first
  int nodes = 0;                                // the last cloud's node count
  std::string ended; // why: "target reached", "passes used", "max_nodes reached", "until reached"
};

/// The nodes marked by Doerfler's rule: the fewest of the largest eta_I^2 whose sum reaches
/// `fraction` of the whole, and every node within 1e-9 (relative) of the last one's value, so
/// that nodes whose values are equal up to rounding (mirror images) are marked together.
std::vector<int> doerfler_marking(const std::vector<double>& eta2, double fraction);

/// Boxes that halve the spacing around each marked node (a box reaching one spacing out of the
/// node), and around those the node's own spacing two spacings out where the cloud is coarser
/// there, so that neighbouring spacings differ by a factor of 2 at most.
std::vector<geometry::Refinement> refinement_around(const geometry::NodeCloud& cloud,
                                                    const std::vector<int>& marked, double spacing,
                                                    const std::vector<geometry::Refinement>& now);

/// The cloud after an estimate e on `cloud` (made of the boxes `now`): Doerfler's marking of its
/// nodes and the boxes around them added to `now`; not allowed when it has more than max_nodes
/// nodes (logged).
struct NextCloud {
  std::vector<int> marked;
  std::vector<geometry::Refinement> refinement;
  geometry::NodeCloud cloud;
  bool allowed = true;
};
NextCloud next_cloud(const spec::ProblemSpec& spec, const geometry::NodeCloud& cloud,
                     const std::vector<geometry::Refinement>& now, const ErrorEstimate& e);

/// Solves the problem on the discretisation of the spec it is given and returns its estimate.
using PilotSolve = std::function<ErrorEstimate(const spec::ProblemSpec&)>;

/// The refinement loop: pilot solves, each followed, while its estimate is above the target and
/// passes remain, by the refinement of its marked nodes unless that exceeds max_nodes.
/// Identical on every rank (the estimates are). Logs each pass.
Adaptation adapt_nodes(const spec::ProblemSpec& spec, const PilotSolve& solve);

/// A problem as it is solved: its spec, with the cloud refined where discretisation.adapt asks
/// for it, and the record of that refinement.
struct AdaptedProblem {
  spec::ProblemSpec spec;
  std::optional<Adaptation> adaptation;
};

/// The problem refined by adapt_nodes with `solve` as its pilot, or as it is without adapt or
/// when its cloud is refined during the analysis (adapt.every).
AdaptedProblem adapted_problem(const spec::ProblemSpec& spec, const PilotSolve& solve);

/// Keeps the record of the refinement in an analysis' result, and its pilots' wall time as the
/// phase adapt_pilots.
template <class Result> void record_adaptation(const AdaptedProblem& p, Result& r) {
  if (!p.adaptation) return;
  for (const AdaptPass& pass : p.adaptation->passes) r.timer.add("adapt_pilots", pass.seconds);
  r.adaptation = p.adaptation;
}

/// The spec of a pilot solve of an elastoplastic schedule: each step in at most
/// pilot_increments increments, no checkpoints and no output lines.
spec::ProblemSpec pilot_spec(const spec::ProblemSpec& spec);

} // namespace mf::implicit
