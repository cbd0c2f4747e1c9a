// libmeshfree_gmsh.so: meshes a plane body, or its prism with tetrahedra, with gmsh's C++ API
// (Geuzaine & Remacle 2009; gmsh reference manual, "Gmsh application programming interface") for
// fem/mesh_generation, which loads it when a mesh is to be made (see
// include/meshfree/fem/gmsh_mesher.hpp for why).
#include "meshfree/fem/gmsh_mesher.hpp"
#include <algorithm>
#include <cmath>
#include <gmsh.h>

namespace {

using mf::fem::gmsh_mesher::Request;
using mf::fem::gmsh_mesher::Result;

/// gmsh's API is one global model: initialised here and finalised on every way out.
struct Session {
  Session() {
    gmsh::initialize(0, nullptr, false); // no user configuration files: the mesh is reproducible
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::model::add("body");
  }
  ~Session() { gmsh::finalize(); }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

bool volume(const Request& q) {
  return q.element_type == 4 || q.element_type == 11;
}

/// The plane surface inside the polygon of n vertices xy (x0, y0, x1, y1, ...) at height z; where
/// `centres` is given (cx, cy of each edge, NaN for a straight one) an edge is the circular arc
/// about its centre.
int plane_polygon(const double* xy, std::size_t n, double z, const double* centres = nullptr) {
  namespace occ = gmsh::model::occ;
  std::vector<int> points, lines;
  for (std::size_t i = 0; i < n; ++i) points.push_back(occ::addPoint(xy[2 * i], xy[2 * i + 1], z));
  for (std::size_t i = 0; i < n; ++i) {
    const int to = points[(i + 1) % n];
    if (centres && !std::isnan(centres[2 * i]))
      lines.push_back(
          occ::addCircleArc(points[i], occ::addPoint(centres[2 * i], centres[2 * i + 1], z), to));
    else
      lines.push_back(occ::addLine(points[i], to));
  }
  return occ::addPlaneSurface({occ::addCurveLoop(lines)});
}

/// The body as OpenCASCADE entities: the polygon as a surface, cut by the holes (discs and
/// polygons; a hole may
/// cross the outline, as the quarter models' holes at a corner do), at z = z0; for tetrahedra
/// that surface extruded by `depth` along z into a volume, and the spheres' balls cut from it
/// (a ball may cross the prism's faces, as an octant model's cavity at a corner does).
void build_body(const Request& q) {
  namespace occ = gmsh::model::occ;
  const double z = volume(q) ? q.z0 : 0.0;
  const std::size_t n = q.polygon.size() / 2;
  gmsh::vectorpair body{
      {2, plane_polygon(q.polygon.data(), n, z,
                        q.polygon_centres.empty() ? nullptr : q.polygon_centres.data())}};
  if (!q.holes.empty() || !q.polygon_hole_sizes.empty()) {
    gmsh::vectorpair holes, out;
    std::vector<gmsh::vectorpair> map;
    for (std::size_t h = 0; h + 2 < q.holes.size(); h += 3)
      holes.push_back(
          {2, occ::addDisk(q.holes[h], q.holes[h + 1], z, q.holes[h + 2], q.holes[h + 2])});
    std::size_t first = 0;
    for (const int size : q.polygon_hole_sizes) {
      holes.push_back({2, plane_polygon(q.polygon_holes.data() + 2 * first, size, z)});
      first += static_cast<std::size_t>(size);
    }
    occ::cut(body, holes, out, map);
    body = out;
  }
  if (volume(q)) {
    gmsh::vectorpair out, solids, balls, cut;
    occ::extrude(body, 0.0, 0.0, q.depth, out);
    for (const auto& e : out)
      if (e.first == 3) solids.push_back(e);
    for (std::size_t s = 0; s + 3 < q.spheres.size(); s += 4)
      balls.push_back(
          {3, occ::addSphere(q.spheres[s], q.spheres[s + 1], q.spheres[s + 2], q.spheres[s + 3])});
    if (!balls.empty()) {
      std::vector<gmsh::vectorpair> map;
      occ::cut(solids, balls, cut, map);
    }
  }
  occ::synchronize();
}

/// The element size: `size`, and each refinement box's size inside it (growing back to `size`
/// over one `size` outside), the smallest winning.
void set_sizes(const Request& q) {
  namespace field = gmsh::model::mesh::field;
  gmsh::option::setNumber("Mesh.MeshSizeMax", q.size);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  if (q.boxes.empty()) return;
  std::vector<double> boxes;
  for (std::size_t b = 0; b + 6 < q.boxes.size(); b += 7) {
    const int f = field::add("Box");
    field::setNumber(f, "XMin", q.boxes[b]);
    field::setNumber(f, "YMin", q.boxes[b + 1]);
    field::setNumber(f, "XMax", q.boxes[b + 2]);
    field::setNumber(f, "YMax", q.boxes[b + 3]);
    if (volume(q)) { // the box's range of the prism's depth
      field::setNumber(f, "ZMin", std::max(q.z0, q.boxes[b + 4]));
      field::setNumber(f, "ZMax", std::min(q.z0 + q.depth, q.boxes[b + 5]));
    }
    field::setNumber(f, "VIn", q.boxes[b + 6]);
    field::setNumber(f, "VOut", q.size);
    field::setNumber(f, "Thickness", q.size);
    boxes.push_back(f);
  }
  const int smallest = field::add("Min");
  field::setNumbers(smallest, "FieldsList", boxes);
  field::setAsBackgroundMesh(smallest);
}

void mesh(const Request& q, Result& r) {
  build_body(q);
  set_sizes(q);
  // Frontal-Delaunay (6): gmsh 4.8's quadrilateral algorithm (8) crashes with a size field.
  gmsh::option::setNumber("Mesh.Algorithm", 6);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay
  if (q.element_type == 3 || q.element_type == 16) {
    gmsh::option::setNumber("Mesh.RecombineAll", 1);
    gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 3); // Blossom, full-quad
  }
  const int dim = volume(q) ? 3 : 2;
  gmsh::model::mesh::generate(dim);
  if (q.element_type == 16 || q.element_type == 11) {
    // serendipity quadrilaterals: no centre node (the 10-node tetrahedron has none either);
    // the new nodes of boundary edges and faces lie on the geometry
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
    gmsh::model::mesh::setOrder(2);
  }
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(r.element_types, tags, nodes, dim);
  for (const auto& t : tags) r.element_counts.push_back(t.size());
  if (!nodes.empty()) r.connectivity = nodes[0];
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(r.node_tags, r.xyz, parametric);
}

} // namespace

extern "C" void meshfree_gmsh_mesh(const Request& q, Result& r) {
  r = Result{};
  try {
    Session session;
    try {
      mesh(q, r);
    } catch (...) {
      gmsh::logger::getLastError(r.error);
      if (r.error.empty()) r.error = "no reason given";
    }
  } catch (...) {
    r.error = "gmsh could not start";
  }
}
