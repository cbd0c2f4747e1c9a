#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/timer.hpp"
#include <algorithm>
#include <numeric>
#include <utility>

namespace mf::implicit {

// [Doerfler 1996]: bulk marking, largest first.
std::vector<int> doerfler_marking(const std::vector<double>& eta2, double fraction) {
  std::vector<int> order(eta2.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return eta2[a] > eta2[b]; });
  const double whole = std::accumulate(eta2.begin(), eta2.end(), 0.0);
  if (whole <= 0.0) return {};
  double sum = 0.0;
  std::size_t n = 0;
  while (n < order.size() && sum < fraction * whole) sum += eta2[order[n++]];
  const double last = eta2[order[n - 1]];
  while (n < order.size() && eta2[order[n]] >= last * (1.0 - 1e-9)) ++n;
  order.resize(n);
  std::sort(order.begin(), order.end());
  return order;
}

namespace {

/// The square of half-width `reach` around x with the given node spacing.
geometry::Refinement box_around(const Vec2& x, double reach, double spacing) {
  const Vec2 r(reach, reach);
  return {BoundingBox{x - r, x + r}, spacing};
}

/// True where the cloud of `boxes` is coarser than h somewhere on the square of half-width
/// `reach` around x (its corners and the middles of its sides).
bool coarser_around(const Vec2& x, double reach, double h, double spacing,
                    const std::vector<geometry::Refinement>& boxes) {
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i)
      if ((i || j) &&
          geometry::local_spacing(x + reach * Vec2(i, j), spacing, boxes) > h * (1.0 + 1e-9))
        return true;
  return false;
}

/// Adds the boxes that halve the spacing around node I, and the graded box around them.
void refine_node(const geometry::NodeCloud& cloud, int I, double spacing,
                 std::vector<geometry::Refinement>& boxes) {
  const double h = cloud.spacing[I];
  boxes.push_back(box_around(cloud.x[I], 2.0 * h, 0.5 * h));
  if (coarser_around(cloud.x[I], 4.0 * h, h, spacing, boxes))
    boxes.push_back(box_around(cloud.x[I], 4.0 * h, h));
}

} // namespace

std::vector<geometry::Refinement> refinement_around(const geometry::NodeCloud& cloud,
                                                    const std::vector<int>& marked, double spacing,
                                                    const std::vector<geometry::Refinement>& now) {
  std::vector<geometry::Refinement> boxes = now;
  for (int I : marked) refine_node(cloud, I, spacing, boxes);
  return boxes;
}

spec::ProblemSpec pilot_spec(const spec::ProblemSpec& spec) {
  spec::ProblemSpec pilot = spec;
  const int most = spec.galerkin().discretisation.adapt->pilot_increments;
  for (spec::LoadStep& s : pilot.galerkin().steps) s.increments = std::min(s.increments, most);
  pilot.galerkin().lines.clear();
  pilot.galerkin().record_increment_parameters = false;
  return pilot;
}

namespace {

/// One pilot solve on the cloud of `boxes`, logged.
std::pair<AdaptPass, ErrorEstimate> pilot(spec::ProblemSpec& pass_spec, int pass,
                                          const std::vector<geometry::Refinement>& boxes,
                                          const PilotSolve& solve) {
  const spec::AdaptSpec& a = *pass_spec.galerkin().discretisation.adapt;
  const auto start = std::chrono::steady_clock::now();
  pass_spec.galerkin().discretisation.refinement = boxes;
  ErrorEstimate e = solve(pass_spec);
  AdaptPass p;
  p.nodes = static_cast<int>(e.node_eta2.size());
  p.estimate = e.relative();
  p.seconds = seconds_since(start);
  log::info("adapt: pass ", pass + 1, " of at most ", a.passes, ", ", p.nodes,
            " nodes, estimated error ", p.estimate, " (target ", a.target, "), ",
            log::duration(p.seconds));
  return {p, std::move(e)};
}

} // namespace

NextCloud next_cloud(const spec::ProblemSpec& spec, const geometry::NodeCloud& cloud,
                     const std::vector<geometry::Refinement>& now, const ErrorEstimate& e) {
  const spec::DiscretisationSpec& d = spec.galerkin().discretisation;
  NextCloud next;
  next.marked = doerfler_marking(e.node_eta2, d.adapt->fraction);
  next.refinement = refinement_around(cloud, next.marked, d.spacing, now);
  next.cloud = geometry::generate_nodes(spec.domain, d.spacing, next.refinement);
  const int n = static_cast<int>(next.cloud.x.size());
  next.allowed = n <= d.adapt->max_nodes;
  if (!next.allowed)
    log::info("adapt: the next cloud would have ", n, " nodes, more than max_nodes");
  return next;
}

Adaptation adapt_nodes(const spec::ProblemSpec& spec, const PilotSolve& solve) {
  const spec::DiscretisationSpec& d = spec.galerkin().discretisation;
  const spec::AdaptSpec& a = *d.adapt;
  Adaptation out;
  out.refinement = d.refinement;
  // The cloud of out.refinement, as the pilot's model has it (nominal spacings): the nodes
  // marked are its indices.
  geometry::NodeCloud cloud = geometry::generate_nodes(spec.domain, d.spacing, out.refinement);
  spec::ProblemSpec pass_spec = spec;
  for (int pass = 0; out.ended.empty(); ++pass) {
    const auto [p, e] = pilot(pass_spec, pass, out.refinement, solve);
    out.passes.push_back(p);
    out.nodes = p.nodes;
    if (p.estimate <= a.target) {
      out.ended = "target reached";
    } else if (pass + 1 >= a.passes) {
      out.ended = "passes used";
    } else {
      NextCloud next = next_cloud(spec, cloud, out.refinement, e);
      if (!next.allowed) {
        out.ended = "max_nodes reached";
      } else {
        out.passes.back().marked = static_cast<int>(next.marked.size());
        out.refinement = std::move(next.refinement);
        out.nodes = static_cast<int>(next.cloud.x.size());
        cloud = std::move(next.cloud);
      }
    }
  }
  return out;
}

AdaptedProblem adapted_problem(const spec::ProblemSpec& spec, const PilotSolve& solve) {
  AdaptedProblem p{spec, std::nullopt};
  const auto& adapt = spec.is_galerkin() ? spec.galerkin().discretisation.adapt : std::nullopt;
  if (!adapt || adapt->every > 0) return p; // no pilots, or none before the analysis
  p.adaptation = adapt_nodes(spec, solve);
  p.spec.galerkin().discretisation.refinement = p.adaptation->refinement;
  return p;
}

} // namespace mf::implicit
