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

gmsh_outline::Function reader() {
  static gmsh_outline::Function function = nullptr;
  if (function) return function;
  std::string tried;
  function = reinterpret_cast<gmsh_outline::Function>(
      plugin_function(kGmshLibrary, gmsh_outline::kEntry, tried));
  if (function) return function;
  fail("reading a geometry file needs gmsh's reader, ", kGmshLibrary, ", which cannot be loaded",
       tried, " (scripts/setup.sh installs gmsh and builds it)");
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
  for (const gmsh_outline::Group& g : r.groups)
    (g.dimension == 1 ? out.curve_groups : out.surface_groups).push_back(g.name);
  if (r.loops.empty()) fail(path, ": its surfaces have no boundary");
  // The outline is the loop of largest area; every other loop must be a hole inside it.
  std::vector<double> area;
  for (const auto& loop : r.loops) area.push_back(std::abs(loop_area(loop)));
  const std::size_t outer =
      static_cast<std::size_t>(std::max_element(area.begin(), area.end()) - area.begin());
  std::vector<std::vector<Curve>> holes;
  for (std::size_t k = 0; k < r.loops.size(); ++k) {
    if (k == outer) continue;
    const Vec2 p = r.loops[k].front().point(0.5);
    if (!inside_loop(r.loops[outer], p))
      fail(path, ": its surfaces make more than one body (a boundary loop lies outside another); "
                 "a plane model reads one body");
    holes.push_back(r.loops[k]);
  }
  // A round hole is a circle, as in the built-in shapes (integrated on its exact region).
  std::vector<Circle> circles;
  holes.erase(std::remove_if(holes.begin(), holes.end(),
                             [&](const std::vector<Curve>& h) {
                               const std::optional<Circle> c = whole_circle(h);
                               if (c) circles.push_back(*c);
                               return c.has_value();
                             }),
              holes.end());
  out.body = Domain::from_loops(r.loops[outer], std::move(holes));
  for (const Circle& c : circles) out.body.add_hole(c);
  return out;
}

} // namespace mf::geometry
