#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/plugin.hpp"
#include "meshfree/core/progress.hpp"
#include "meshfree/fem/gmsh_mesher.hpp"
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace mf::fem {

namespace {

/// The mesher in gmsh's library (core/plugin.hpp).
gmsh_mesher::Function mesher() {
  return reinterpret_cast<gmsh_mesher::Function>(gmsh_function(
      gmsh_mesher::kEntry, "discretisation.fem: meshing the geometry",
      "scripts/setup.sh installs gmsh and builds it; or give discretisation.fem.mesh"));
}

/// Appends the starts of a loop's pieces (x, y) to `points` and, with `arcs`, each piece's arc
/// centre (cx, cy; NaN, NaN for a segment) to `centres`.
void add_loop(const std::vector<geometry::Curve>& loop, bool arcs, std::vector<double>& points,
              std::vector<double>& centres) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const geometry::Curve& c : loop) {
    const Vec2 p = c.point(0.0);
    points.insert(points.end(), {p.x(), p.y()});
    if (!arcs) continue;
    const bool arc = c.kind == geometry::Curve::Kind::Arc;
    centres.insert(centres.end(), {arc ? c.center.x() : nan, arc ? c.center.y() : nan});
  }
}

/// The request for the body (its outline, holes, refinement boxes and size).
gmsh_mesher::Request request(const geometry::Domain& domain, double size,
                             const std::vector<geometry::Refinement>& refinement) {
  MF_REQUIRE(size > 0.0, "mesh size must be positive");
  gmsh_mesher::Request q;
  add_loop(domain.outline(), domain.has_arcs(), q.polygon, q.polygon_centres);
  for (const geometry::Circle& c : domain.holes())
    q.holes.insert(q.holes.end(), {c.center.x(), c.center.y(), c.radius});
  bool curved_holes = false;
  for (const geometry::OutlineHole& h : domain.outline_holes())
    curved_holes = curved_holes || h.kind == geometry::OutlineHole::Kind::Loop;
  const auto add_polygon = [&](const std::vector<Vec2>& v) {
    for (const Vec2& p : v) q.polygon_holes.insert(q.polygon_holes.end(), {p.x(), p.y()});
    q.polygon_hole_sizes.push_back(static_cast<int>(v.size()));
    if (curved_holes) // beside holes with arcs, its edges straight
      q.polygon_hole_centres.insert(q.polygon_hole_centres.end(), 2 * v.size(),
                                    std::numeric_limits<double>::quiet_NaN());
  };
  for (const geometry::OutlineHole& h : domain.outline_holes()) {
    if (h.kind == geometry::OutlineHole::Kind::Loop) {
      add_loop(h.curves, true, q.polygon_holes, q.polygon_hole_centres);
      q.polygon_hole_sizes.push_back(static_cast<int>(h.curves.size()));
      continue;
    }
    if (h.kind == geometry::OutlineHole::Kind::Polygon) {
      add_polygon(h.vertices);
      continue;
    }
    // A slot: the rectangle between its ends' centres, and a disc at each end.
    for (const Vec2& c : {h.a, h.b}) q.holes.insert(q.holes.end(), {c.x(), c.y(), h.half_width});
    const Vec2 d = h.b - h.a;
    if (d.norm() == 0.0) continue;
    const Vec2 n = h.half_width * Vec2(-d.y(), d.x()) / d.norm();
    add_polygon({h.a - n, h.b - n, h.b + n, h.a + n});
  }
  for (const geometry::Curve& c : domain.interfaces()) {
    const Vec2 a = c.point(0.0), b = c.point(1.0);
    const bool arc = c.kind == geometry::Curve::Kind::Arc;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    q.interfaces.insert(q.interfaces.end(), {a.x(), a.y(), b.x(), b.y(), arc ? c.center.x() : nan,
                                             arc ? c.center.y() : nan});
  }
  for (const geometry::Refinement& r : refinement)
    q.boxes.insert(q.boxes.end(), {r.box.lo.x(), r.box.lo.y(), r.box.hi.x(), r.box.hi.y(), r.z_lo,
                                   r.z_hi, r.spacing});
  q.size = size;
  return q;
}

/// Runs gmsh on the request, `nodes` the expected node count for the log of a large mesh.
gmsh_mesher::Result run_gmsh(const gmsh_mesher::Request& q, double nodes) {
  const gmsh_mesher::Function mesh_with_gmsh = mesher();
  // gmsh tells no share done: a large mesh gets a line before and one after, with its time.
  const bool report = 2.0 * nodes >= log::kProgressUnknowns;
  if (report) log::info("meshing the body with gmsh: about ", std::lround(nodes), " nodes or more");
  const auto began = std::chrono::steady_clock::now();
  gmsh_mesher::Result r;
  mesh_with_gmsh(q, r);
  if (!r.error.empty()) fail("discretisation.fem: gmsh could not mesh the body: ", r.error);
  if (report)
    log::info("meshed the body: ", r.node_tags.size(), " nodes, ",
              std::accumulate(r.element_counts.begin(), r.element_counts.end(), std::size_t{0}),
              " elements in ",
              log::duration(
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count()));
  return r;
}

/// The element types gmsh made must all be `wanted` (`name` in messages).
void require_type(const gmsh_mesher::Result& r, int wanted, const char* name, const char* remedy) {
  if (r.element_types.empty()) fail("discretisation.fem: gmsh made no element of the body");
  for (std::size_t k = 0; k < r.element_types.size(); ++k)
    if (r.element_types[k] != wanted)
      fail("discretisation.fem.element: gmsh left ", r.element_counts[k], " elements of gmsh type ",
           r.element_types[k], " in a ", name, " mesh of the body", remedy);
}

/// Numbers the nodes in the order the elements first name them (so nodes no element uses are
/// dropped); `at(i)` receives the coordinates of gmsh's i-th listed node.
template <class At> std::vector<int> number_nodes(const gmsh_mesher::Result& r, At&& at) {
  std::unordered_map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < r.node_tags.size(); ++i) position[r.node_tags[i]] = i;
  std::unordered_map<std::size_t, int> index;
  std::vector<int> connectivity;
  for (std::size_t tag : r.connectivity) {
    auto [it, added] = index.emplace(tag, static_cast<int>(index.size()));
    if (added) {
      const auto p = position.find(tag);
      MF_REQUIRE(p != position.end(), "gmsh named a node it did not list: ", tag);
      at(p->second);
    }
    connectivity.push_back(it->second);
  }
  return connectivity;
}

} // namespace

Mesh mesh_domain(const geometry::Domain& domain, double size,
                 const std::vector<geometry::Refinement>& refinement, ElementType type) {
  gmsh_mesher::Request q = request(domain, size, refinement);
  q.element_type = gmsh_element_type(type);
  const gmsh_mesher::Result r = run_gmsh(q, domain.area_estimate() / (size * size));
  require_type(r, q.element_type, element_name(type), "; give element t3, or a mesh file");
  Mesh mesh;
  mesh.type = type;
  mesh.connectivity =
      number_nodes(r, [&](std::size_t i) { mesh.x.emplace_back(r.xyz[3 * i], r.xyz[3 * i + 1]); });
  check_mesh(mesh, "the gmsh mesh of the body");
  orient_counter_clockwise(mesh, "the gmsh mesh of the body");
  return mesh;
}

TetMesh mesh_prism(const geometry::Prism& body, double size,
                   const std::vector<geometry::Refinement>& refinement, bool quadratic) {
  const geometry::Domain& domain = body.section;
  const double depth = body.depth;
  MF_REQUIRE(depth > 0.0, "the prism's depth must be positive");
  gmsh_mesher::Request q = request(domain, size, refinement);
  q.element_type = quadratic ? 11 : 4;
  q.z0 = body.z0;
  q.depth = depth;
  for (const geometry::Sphere& s : body.spheres)
    q.spheres.insert(q.spheres.end(), {s.center.x(), s.center.y(), s.center.z(), s.radius});
  const gmsh_mesher::Result r = run_gmsh(q, domain.area_estimate() * depth / (size * size * size));
  require_type(r, q.element_type, quadratic ? "tet10" : "tet4", "");
  TetMesh mesh;
  mesh.quadratic = quadratic;
  mesh.connectivity = number_nodes(r, [&](std::size_t i) {
    mesh.x.emplace_back(r.xyz[3 * i], r.xyz[3 * i + 1], r.xyz[3 * i + 2]);
  });
  orient_tetrahedra(mesh, "the gmsh mesh of the body");
  return mesh;
}

TetMesh mesh_prism(const geometry::Domain& domain, double z0, double depth, double size,
                   const std::vector<geometry::Refinement>& refinement, bool quadratic) {
  return mesh_prism(geometry::Prism{domain, z0, depth, {}}, size, refinement, quadratic);
}

} // namespace mf::fem
