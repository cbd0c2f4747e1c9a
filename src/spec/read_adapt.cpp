// discretisation.adapt: error-driven refinement of a plane meshfree body's nodes.
#include "meshfree/core/memory.hpp"
#include "meshfree/spec/galerkin_read.hpp"

namespace mf::spec {

namespace {
/// The keys of an `adapt` map into r (absent keys keep r's defaults).
void read_adapt_keys(KeyReader& a, AdaptSpec& r) {
  r.target = a.positive("target", r.target);
  if (r.target >= 1.0)
    a.error("target",
            "is a relative error: expected a value below 1, got " + std::to_string(r.target));
  r.fraction = a.positive("fraction", r.fraction);
  if (r.fraction > 1.0)
    a.error("fraction", "is a share of the estimated error: expected (0, 1], got " +
                            std::to_string(r.fraction));
  r.passes = a.integer("passes", r.passes, 1, 20);
  r.max_nodes = a.positive("max_nodes", r.max_nodes);
  r.every = a.integer("every", r.every, 0, 1000000);
  if (r.every > 0 && a.has("pilot_increments"))
    a.error("pilot_increments", "there are no pilot solves when the cloud is refined during the "
                                "analysis (every: " +
                                    std::to_string(r.every) + ")");
  r.pilot_increments = a.integer("pilot_increments", r.pilot_increments, 1, 1000000);
  if (r.every == 0 && a.has("until"))
    a.error("until", "ends refinement during the analysis, which needs every: N (N > 0)");
  r.until = a.integer("until", r.until, 1, 1000000);
  if (r.until > 0 && r.until < r.every)
    a.error("until", "is " + std::to_string(r.until) +
                         ", before the first increment estimated (every: " +
                         std::to_string(r.every) + "): no refinement would be made");
  a.finish();
}
} // namespace

std::optional<AdaptSpec> read_adapt(KeyReader& d, int dim, const DiscretisationSpec& s,
                                    const LinearSolverSpec& solver) {
  if (!d.has("adapt")) return std::nullopt;
  // `adapt: off` runs the file's own cloud, so that a file that adapts can be run uniform, or by
  // finite elements, with --set discretisation.adapt=off; `adapt: on` takes every default.
  const YAML::Node given = d.raw("adapt");
  const std::string word = given.IsScalar() ? given.Scalar() : "";
  if (word == "off" || word == "false") return std::nullopt;
  const bool defaults = word == "on" || word == "true";
  if (given.IsScalar() && !defaults)
    d.error("adapt", "expected on, off or a map of keys, got " + one_line(word));
  if (dim != 2)
    d.error("adapt", "error-driven refinement is made for plane bodies, not for this model");
  if (s.method != Method::Meshfree)
    d.error("adapt", "error-driven refinement places meshfree nodes: it needs method: meshfree");
  AdaptSpec r;
  if (!defaults) {
    KeyReader a = d.map("adapt");
    read_adapt_keys(a, r);
  }
  require_memory(d.path_of("adapt") + ".max_nodes", "nodes of the refined cloud", r.max_nodes,
                 bytes_per_node(solver, r.max_nodes));
  return r;
}

} // namespace mf::spec
