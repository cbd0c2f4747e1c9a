#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/core/error.hpp"
#include <gmsh.h>
#include <unordered_map>

namespace mf::fem {

namespace {

/// gmsh's API is one global model: initialised here and finalised on every way out.
struct GmshSession {
  GmshSession() {
    gmsh::initialize(0, nullptr, false); // no user configuration files: the mesh is reproducible
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::model::add("body");
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

/// The body as one OpenCASCADE surface: the polygon, cut by the holes (a hole may cross the
/// outline, as the quarter models' holes at a corner do).
void build_surface(const geometry::Domain& domain) {
  namespace occ = gmsh::model::occ;
  const std::vector<Vec2>& v = domain.vertices();
  std::vector<int> points, lines;
  for (const Vec2& p : v) points.push_back(occ::addPoint(p.x(), p.y(), 0.0));
  for (std::size_t i = 0; i < v.size(); ++i)
    lines.push_back(occ::addLine(points[i], points[(i + 1) % v.size()]));
  const int surface = occ::addPlaneSurface({occ::addCurveLoop(lines)});
  if (!domain.holes().empty()) {
    gmsh::vectorpair holes, out;
    std::vector<gmsh::vectorpair> map;
    for (const geometry::Circle& c : domain.holes())
      holes.push_back({2, occ::addDisk(c.center.x(), c.center.y(), 0.0, c.radius, c.radius)});
    occ::cut({{2, surface}}, holes, out, map);
  }
  occ::synchronize();
}

/// The element size: `size`, and each refinement box's spacing inside it, the smallest winning.
void set_sizes(double size, const std::vector<geometry::Refinement>& refinement) {
  namespace field = gmsh::model::mesh::field;
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  if (refinement.empty()) return;
  std::vector<double> boxes;
  for (const geometry::Refinement& r : refinement) {
    const int f = field::add("Box");
    field::setNumber(f, "VIn", r.spacing);
    field::setNumber(f, "VOut", size);
    field::setNumber(f, "XMin", r.box.lo.x());
    field::setNumber(f, "XMax", r.box.hi.x());
    field::setNumber(f, "YMin", r.box.lo.y());
    field::setNumber(f, "YMax", r.box.hi.y());
    field::setNumber(f, "Thickness", size);
    boxes.push_back(f);
  }
  const int smallest = field::add("Min");
  field::setNumbers(smallest, "FieldsList", boxes);
  field::setAsBackgroundMesh(smallest);
}

int gmsh_type_of(ElementType type) {
  return type == ElementType::T3 ? 2 : type == ElementType::Q4 ? 3 : 16;
}

/// The 2-D elements of the generated mesh as a Mesh, nodes numbered in gmsh's order, those no
/// element uses dropped.
Mesh collect(ElementType type) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, 2);
  Mesh mesh;
  mesh.type = type;
  for (std::size_t k = 0; k < types.size(); ++k) {
    if (types[k] != gmsh_type_of(type))
      fail("discretisation.fem.element: gmsh left ", element_tags[k].size(),
           " elements of gmsh type ", types[k], " in a ", element_name(type),
           " mesh of the body; give element t3, or a mesh file");
  }
  if (types.empty()) fail("discretisation.fem: gmsh made no element of the body");
  std::vector<std::size_t> node_tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(node_tags, xyz, parametric);
  std::unordered_map<std::size_t, Vec2> position;
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    position[node_tags[i]] = Vec2(xyz[3 * i], xyz[3 * i + 1]);
  std::unordered_map<std::size_t, int> index;
  for (std::size_t tag : element_nodes[0]) {
    auto [it, added] = index.emplace(tag, mesh.node_count());
    if (added) mesh.x.push_back(position.at(tag));
    mesh.connectivity.push_back(it->second);
  }
  return mesh;
}

} // namespace

Mesh mesh_domain(const geometry::Domain& domain, double size,
                 const std::vector<geometry::Refinement>& refinement, ElementType type) {
  MF_REQUIRE(size > 0.0, "mesh size must be positive");
  GmshSession session;
  Mesh mesh;
  try {
    build_surface(domain);
    set_sizes(size, refinement);
    gmsh::option::setNumber("Mesh.Algorithm", 6); // Frontal-Delaunay
    if (type != ElementType::T3) {
      gmsh::option::setNumber("Mesh.RecombineAll", 1);
      gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 3); // Blossom, full-quad
    }
    gmsh::model::mesh::generate(2);
    if (type == ElementType::Q8) {
      gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1); // serendipity: no centre node
      gmsh::model::mesh::setOrder(2);
    }
    mesh = collect(type);
  } catch (const Error&) {
    throw;
  } catch (...) {
    std::string reason;
    gmsh::logger::getLastError(reason);
    fail("discretisation.fem: gmsh could not mesh the body: ",
         reason.empty() ? std::string("no reason given") : reason);
  }
  check_mesh(mesh, "the gmsh mesh of the body");
  orient_counter_clockwise(mesh, "the gmsh mesh of the body");
  return mesh;
}

} // namespace mf::fem
