#include "meshfree/implicit/adaptivity_output.hpp"
#include <cmath>
#include <sstream>

namespace mf::implicit {

namespace {
/// The last cloud's boxes as a YAML flow list that `discretisation.refinement` takes: a
/// finite-element run given them (--set "discretisation.refinement=$(cat FILE)") meshes the
/// body graded by the same estimate. The nodes follow them too, but the adapted cloud's graded
/// supports (geometry::grade_spacing) come only with `adapt`.
std::string refinement_yaml(const std::vector<geometry::Refinement>& boxes) {
  std::ostringstream s;
  s.precision(17);
  s << "# discretisation.refinement of the adapted cloud, the problem's own boxes first: a\n"
       "# finite-element mesh graded as the cloud; a meshfree cloud of them has the supports of\n"
       "# the adapted one (graded across each change of spacing) only with discretisation.adapt\n[";
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const geometry::Refinement& r = boxes[k];
    s << (k ? ",\n " : "") << "{box: [[" << r.box.lo.x() << ", " << r.box.lo.y() << "], ["
      << r.box.hi.x() << ", " << r.box.hi.y() << "]], spacing: " << r.spacing << "}";
  }
  s << "]\n";
  return s.str();
}
} // namespace

io::Json adaptation_json(const spec::ProblemSpec& spec, const Adaptation& a,
                         const ErrorEstimate& final_estimate) {
  const spec::AdaptSpec& s = *spec.galerkin().discretisation.adapt;
  std::vector<double> nodes, estimate, marked, increment;
  for (const AdaptPass& p : a.passes) {
    nodes.push_back(p.nodes);
    estimate.push_back(p.estimate);
    marked.push_back(p.marked);
    increment.push_back(p.increment);
  }
  // Their wall times: the log, and time_s.adapt_pilots (or time_s.adapt) together.
  io::Json passes;
  passes.set("nodes", nodes).set("estimate", estimate).set("marked", marked);
  if (s.every > 0) passes.set("increment", increment); // the increment estimated
  io::Json j;
  j.set("target", s.target).set("fraction", s.fraction);
  if (s.every > 0) j.set("every", s.every);
  if (s.until > 0) j.set("until", s.until);
  j.set("ended", a.ended)
      .set("refinement_boxes", static_cast<long>(a.refinement.size()))
      .set(s.every > 0 ? "passes" : "pilot_passes", passes)
      .set("nodes", a.nodes)
      .set("final_estimate", final_estimate.relative())
      .set("target_met", final_estimate.relative() <= s.target);
  return j;
}

void write_adaptation(const spec::ProblemSpec& spec, const Adaptation& a,
                      const ErrorEstimate& final_estimate, long increments,
                      io::OutputDirectory& out) {
  const bool pilots = spec.galerkin().discretisation.adapt->every == 0;
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < a.passes.size(); ++k) {
    const AdaptPass& p = a.passes[k];
    rows.push_back({static_cast<double>(k + 1), pilots ? 1.0 : 0.0, static_cast<double>(p.nodes),
                    2.0 * p.nodes, p.estimate, static_cast<double>(p.marked),
                    static_cast<double>(p.increment)});
  }
  // The analysis' final state on the last cloud (pilot 0). The wall times are the log's and
  // time_s: the file holds results only.
  rows.push_back({static_cast<double>(a.passes.size() + 1), 0.0, static_cast<double>(a.nodes),
                  2.0 * a.nodes, final_estimate.relative(), 0.0, static_cast<double>(increments)});
  out.write_csv("adapt.csv", {"pass", "pilot", "nodes", "dofs", "estimate", "marked", "increment"},
                rows);
  out.write_text("adapted_refinement.yaml", refinement_yaml(a.refinement));

  const spec::DiscretisationSpec& d = spec.galerkin().discretisation;
  const geometry::NodeCloud cloud = geometry::generate_nodes(spec.domain, d.spacing, a.refinement);
  io::FieldStep step;
  std::vector<double> eta(cloud.x.size());
  for (std::size_t I = 0; I < eta.size() && I < final_estimate.node_eta2.size(); ++I)
    eta[I] = std::sqrt(final_estimate.node_eta2[I]);
  step.scalars.emplace_back("error_indicator", std::move(eta));
  step.scalars.emplace_back("node_spacing", cloud.spacing);
  io::FieldSeries series(out, "error_indicator", cloud.x);
  series.add_step(step);
  series.close();
}

} // namespace mf::implicit
