#include "meshfree/geometry/outline_file.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/input_file.hpp"
#include "meshfree/core/plugin.hpp"
#include "meshfree/geometry/gmsh_outline.hpp"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

namespace mf::geometry {

namespace {

/// The reader in gmsh's library (core/plugin.hpp).
gmsh_outline::Function reader() {
  return reinterpret_cast<gmsh_outline::Function>(
      gmsh_function(gmsh_outline::kEntry, "reading a geometry file",
                    "scripts/setup.sh installs gmsh and builds it"));
}

/// The file's extension in lower case, which must be one gmsh reads as geometry.
void require_geometry_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const char* known : {"step", "stp", "brep", "geo", "msh"})
    if (ext == known) return;
  fail(path, ": not a geometry file meshfree reads (.step, .stp, .brep, .geo or .msh)");
}

/// The circle a loop draws, where it is arcs of one circle only (to 1e-9 of its radius), named
/// as its first.
std::optional<Circle> whole_circle(const std::vector<Curve>& loop) {
  const Curve& first = loop.front();
  double sweep = 0.0;
  for (const Curve& c : loop) {
    if (c.kind != Curve::Kind::Arc || (c.center - first.center).norm() > 1e-9 * first.radius ||
        std::abs(c.radius - first.radius) > 1e-9 * first.radius)
      return std::nullopt;
    sweep += c.theta1 - c.theta0;
  }
  if (std::abs(std::abs(sweep) - 2.0 * std::acos(-1.0)) > 1e-9) return std::nullopt;
  return Circle{first.center, first.radius, first.name};
}

/// The body inside `loops`: the loop of largest area its outline, every other a hole inside it
/// (a whole circle a circle hole, as in the built-in shapes). `what` names it in messages.
Domain body_of(const std::vector<std::vector<Curve>>& loops, const std::string& path,
               const std::string& what) {
  if (loops.empty()) fail(path, ": ", what, " have no boundary");
  std::vector<double> area;
  for (const auto& loop : loops) area.push_back(std::abs(loop_area(loop)));
  const std::size_t outer =
      static_cast<std::size_t>(std::max_element(area.begin(), area.end()) - area.begin());
  std::vector<std::vector<Curve>> holes;
  std::vector<Circle> circles;
  for (std::size_t k = 0; k < loops.size(); ++k) {
    if (k == outer) continue;
    if (!inside_loop(loops[outer], loops[k].front().point(0.5)))
      fail(path, ": ", what, " make more than one body (a boundary loop lies outside another); ",
           "one body is read");
    if (const std::optional<Circle> c = whole_circle(loops[k]))
      circles.push_back(*c);
    else
      holes.push_back(loops[k]);
  }
  Domain body = Domain::from_loops(loops[outer], std::move(holes));
  for (const Circle& c : circles) body.add_hole(c);
  return body;
}

} // namespace

OutlineFile read_outline_file(const std::string& path, double scale) {
  require_regular_file(path, "geometry file");
  require_geometry_extension(path);
  MF_REQUIRE(scale > 0.0 && std::isfinite(scale), "the scale must be positive, got ", scale);
  gmsh_outline::Result r;
  reader()(gmsh_outline::Request{path, scale}, r);
  if (!r.error.empty()) fail(path, ": ", r.error);
  if (r.dimension == 3)
    fail(path, ": holds volumes, a 3D body: a plane model reads a file of surfaces in one plane");
  if (r.dimension < 2) fail(path, ": holds no surface");
  OutlineFile out;
  out.body = body_of(r.loops, path, "its surfaces");
  // Where parts meet inside the body: their boundaries' pieces off the body's boundary, once.
  std::vector<Curve> interfaces;
  const double tol = 1e-9 * out.body.bounds().size().maxCoeff();
  for (const gmsh_outline::Group& g : r.groups) {
    if (g.dimension == 1) {
      FileCurve curve{g.name, {}};
      for (const auto& pieces : g.loops)
        curve.pieces.insert(curve.pieces.end(), pieces.begin(), pieces.end());
      out.curves.push_back(std::move(curve));
    }
    if (g.dimension != 2) continue;
    out.parts.push_back({g.name, body_of(g.loops, path, "the surfaces of group '" + g.name + "'")});
    for (const auto& loop : g.loops)
      for (const Curve& c : loop) {
        const Vec2 mid = c.point(0.5);
        const bool seen = std::any_of(interfaces.begin(), interfaces.end(), [&](const Curve& i) {
          return i.distance_to(mid) <= tol && i.distance_to(c.point(0.0)) <= tol;
        });
        if (!seen && out.body.distance_to_boundary(mid) > tol) interfaces.push_back(c);
      }
  }
  out.body.set_interfaces(std::move(interfaces));
  return out;
}

double file_body_area(const Domain& body) {
  double area = body.area_estimate();
  for (const OutlineHole& h : body.outline_holes()) area -= h.area();
  for (const Circle& c : body.holes()) area -= std::acos(-1.0) * c.radius * c.radius;
  return area;
}

std::optional<Annulus> annulus_of(const Domain& body) {
  if (body.outline().empty() || body.holes().size() != 1 || !body.outline_holes().empty())
    return {};
  const std::optional<Circle> outer = whole_circle(body.outline());
  const Circle& hole = body.holes().front();
  if (!outer || (hole.center - outer->center).norm() > 1e-9 * outer->radius ||
      !(hole.radius < outer->radius))
    return {};
  return Annulus{outer->center, hole.radius, outer->radius};
}

} // namespace mf::geometry
