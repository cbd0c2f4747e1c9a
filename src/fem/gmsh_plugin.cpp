// libmeshfree_gmsh.so: meshes a plane body, or its prism with tetrahedra, with gmsh's C++ API
// (Geuzaine & Remacle 2009; gmsh reference manual, "Gmsh application programming interface") for
// fem/mesh_generation, which loads it when a mesh is to be made (see
// include/meshfree/fem/gmsh_mesher.hpp for why); and reads the boundary of a geometry file's
// surfaces for geometry/outline_file (geometry/gmsh_outline.hpp).
#include "meshfree/fem/gmsh_mesher.hpp"
#include "meshfree/geometry/gmsh_outline.hpp"
#include <algorithm>
#include <cmath>
#include <gmsh.h>
#include <omp.h>

namespace {

using mf::fem::gmsh_mesher::Request;
using mf::fem::gmsh_mesher::Result;

/// gmsh's API is one global model: initialised here and finalised on every way out. gmsh sets
/// OpenMP's thread count for the whole process (General.NumThreads calls omp_set_num_threads, and
/// so does its initialisation), so the session gives the program its own count back when it
/// ends: without that, every run that had read or meshed a geometry went on with one thread.
struct Session {
  const int threads = omp_get_max_threads();
  Session() {
    gmsh::initialize(0, nullptr, false); // no user configuration files: the mesh is reproducible
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::option::setNumber("General.AbortOnError", 0);
    gmsh::model::add("body");
  }
  ~Session() {
    gmsh::finalize();
    omp_set_num_threads(threads);
  }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

/// Runs `work` in a gmsh session; what stops it is told in `error` (gmsh's last error).
template <class Work> void in_session(std::string& error, Work&& work) {
  try {
    Session session;
    try {
      work();
    } catch (...) {
      gmsh::logger::getLastError(error);
      if (error.empty()) error = "no reason given";
    }
  } catch (...) {
    error = "gmsh could not start";
  }
}

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
      const double* centres =
          q.polygon_hole_centres.empty() ? nullptr : q.polygon_hole_centres.data() + 2 * first;
      holes.push_back({2, plane_polygon(q.polygon_holes.data() + 2 * first, size, z, centres)});
      first += static_cast<std::size_t>(size);
    }
    occ::cut(body, holes, out, map);
    body = out;
  }
  if (!q.interfaces.empty()) { // the curves where parts meet, made part of the surface
    gmsh::vectorpair curves, out;
    std::vector<gmsh::vectorpair> map;
    for (std::size_t k = 0; k + 5 < q.interfaces.size(); k += 6) {
      const double* c = q.interfaces.data() + k;
      const int from = occ::addPoint(c[0], c[1], z), to = occ::addPoint(c[2], c[3], z);
      curves.push_back({1, std::isnan(c[4])
                               ? occ::addLine(from, to)
                               : occ::addCircleArc(from, occ::addPoint(c[4], c[5], z), to)});
    }
    occ::fragment(body, curves, out, map);
    body.clear();
    for (const auto& e : out)
      if (e.first == 2) body.push_back(e);
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
  in_session(r.error, [&] { mesh(q, r); });
}

namespace {

namespace outline = mf::geometry::gmsh_outline;
using mf::Vec2;
using mf::geometry::Curve;

/// A piece's point at parameter t (0: its start, 1: its end); the library's Curve functions are
/// not linked into this one.
Vec2 at(const Curve& c, double t) {
  if (c.kind == Curve::Kind::Segment) return c.a + t * (c.b - c.a);
  const double th = c.theta0 + t * (c.theta1 - c.theta0);
  return c.center + c.radius * Vec2(std::cos(th), std::sin(th));
}

/// The points of curve `tag` at parameters `t`, scaled.
std::vector<Vec2> points_of(int tag, const std::vector<double>& t, double scale) {
  std::vector<double> xyz;
  gmsh::model::getValue(1, tag, t, xyz);
  std::vector<Vec2> p;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
    p.emplace_back(scale * xyz[i], scale * xyz[i + 1]);
  return p;
}

/// The centre of the circle through three points (the perpendicular bisectors' meeting point:
/// [Zwillinger 2018], docs/references.md).
Vec2 circle_centre(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d =
      2.0 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
  const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
  return Vec2((a2 * (b.y() - c.y()) + b2 * (c.y() - a.y()) + c2 * (a.y() - b.y())) / d,
              (a2 * (c.x() - b.x()) + b2 * (a.x() - c.x()) + c2 * (b.x() - a.x())) / d);
}

/// True where curve `tag` is an arc of a circle: 17 points along it lie within 1e-9 of its radius
/// of the circle through its first, middle and last (a circle, or OpenCASCADE's disk, whose
/// boundary is an ellipse of equal radii, or a rational spline drawn as a circle).
bool circular(int tag, double t0, double t1, double scale) {
  std::vector<double> t;
  for (int k = 0; k <= 16; ++k) t.push_back(t0 + (t1 - t0) * k / 16.0);
  const std::vector<Vec2> p = points_of(tag, t, scale);
  const double span = (p[8] - p[0]).norm() + (p[16] - p[8]).norm();
  const bool closed = (p[16] - p[0]).norm() < 1e-9 * span;
  const Vec2 c = circle_centre(p[0], p[8], p[closed ? 12 : 16]);
  const double r = (p[0] - c).norm();
  if (!std::isfinite(r) || r > 1e6 * span) return false; // a straight curve
  for (const Vec2& q : p)
    if (std::abs((q - c).norm() - r) > 1e-9 * r) return false;
  return true;
}

/// A circle's arc from its parameter t0 to t1 as arcs of at most a quarter turn.
void add_arcs(int tag, double t0, double t1, const std::string& name, double scale,
              std::vector<Curve>& out) {
  const double pi = std::acos(-1.0);
  const std::vector<Vec2> p =
      points_of(tag, {t0, t0 + (t1 - t0) / 3.0, t0 + 2.0 * (t1 - t0) / 3.0, t1}, scale);
  const Vec2 c = circle_centre(p[0], p[1], p[2]);
  const auto angle = [&](const Vec2& q) { return std::atan2(q.y() - c.y(), q.x() - c.x()); };
  // Each third of the arc turns less than a half turn, so its sense is that of the wrapped turn.
  double sweep = 0.0;
  for (int k = 0; k < 3; ++k) sweep += std::remainder(angle(p[k + 1]) - angle(p[k]), 2.0 * pi);
  // A quarter turn at most: an arc of gmsh's own (the mesher's) is given by its centre, which
  // leaves a half turn's sense undefined.
  const int pieces = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / (0.5 * pi) - 1e-9)));
  for (int k = 0; k < pieces; ++k) {
    Curve a;
    a.kind = Curve::Kind::Arc;
    a.name = name;
    a.center = c;
    a.radius = (p[0] - c).norm();
    a.theta0 = angle(p[0]) + sweep * k / pieces;
    a.theta1 = angle(p[0]) + sweep * (k + 1) / pieces;
    out.push_back(a);
  }
}

/// Curve `tag` as pieces: a line one segment, an arc of a circle arcs, any other curve (a spline, an
/// ellipse, a mesh's polyline) chords through 1,024 samples, each chord as long as the samples'
/// direction stays within 5 degrees of its first (a straight run is one chord).
std::vector<Curve> pieces_of(int tag, const std::string& name, double scale) {
  std::string type;
  gmsh::model::getType(1, tag, type);
  std::vector<double> lo, hi;
  gmsh::model::getParametrizationBounds(1, tag, lo, hi);
  const double t0 = lo.at(0), t1 = hi.at(0);
  std::vector<Curve> out;
  if (type != "Line" && circular(tag, t0, t1, scale)) {
    add_arcs(tag, t0, t1, name, scale, out);
    return out;
  }
  std::vector<Vec2> p = points_of(tag, {t0, t1}, scale);
  if (type != "Line") { // a chord ends where the samples' direction has turned 5 degrees
    std::vector<double> t;
    for (int k = 0; k <= 1024; ++k) t.push_back(t0 + (t1 - t0) * k / 1024.0);
    const std::vector<Vec2> s = points_of(tag, t, scale);
    const double most = std::acos(-1.0) / 36.0;
    p = {s.front()};
    Vec2 first = Vec2::Zero(); // the direction the chord set out in
    for (std::size_t k = 1; k < s.size(); ++k) {
      const Vec2 d = s[k] - s[k - 1];
      if (d.norm() == 0.0) continue;
      const double turn = std::atan2(first.x() * d.y() - first.y() * d.x(), first.dot(d));
      if (first.norm() > 0.0 && std::abs(turn) > most) {
        p.push_back(s[k - 1]);
        first = Vec2::Zero();
      }
      if (first.norm() == 0.0) first = d;
    }
    p.push_back(s.back());
  }
  for (std::size_t k = 1; k < p.size(); ++k) {
    Curve c;
    c.name = name;
    c.a = p[k - 1];
    c.b = p[k];
    out.push_back(c);
  }
  return out;
}

/// The name of curve `tag`: its first physical group's, else "curve<tag>".
std::string curve_name(int tag) {
  std::vector<int> groups;
  gmsh::model::getPhysicalGroupsForEntity(1, tag, groups);
  if (groups.empty()) return "curve" + std::to_string(tag);
  std::string name;
  gmsh::model::getPhysicalName(1, groups.front(), name);
  return name.empty() ? "group" + std::to_string(groups.front()) : name;
}

/// The pieces joined into closed loops, each piece's start on the last one's end; empty with
/// `error` set where one cannot be closed.
std::vector<std::vector<Curve>> chain(const std::vector<Curve>& pieces, double tol,
                                      std::string& error) {
  std::vector<std::vector<Curve>> loops;
  std::vector<bool> used(pieces.size(), false);
  for (std::size_t first = 0; first < pieces.size(); ++first) {
    if (used[first]) continue;
    std::vector<Curve> loop{pieces[first]};
    used[first] = true;
    while ((at(loop.back(), 1.0) - at(loop.front(), 0.0)).norm() > tol) {
      std::size_t next = 0;
      while (next < pieces.size() &&
             (used[next] || (at(pieces[next], 0.0) - at(loop.back(), 1.0)).norm() > tol))
        ++next;
      if (next == pieces.size()) {
        const Vec2 end = at(loop.back(), 1.0);
        error = "the boundary of its surfaces is open at (" + std::to_string(end.x()) + ", " +
                std::to_string(end.y()) + ")";
        return {};
      }
      used[next] = true;
      loop.push_back(pieces[next]);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// The boundary of the union of `surfaces` as closed loops of pieces.
std::vector<std::vector<Curve>> boundary_loops(const gmsh::vectorpair& surfaces, double scale,
                                               double tol, std::string& error) {
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary(surfaces, boundary, true, true, false);
  std::vector<Curve> pieces;
  for (const auto& [dim, signed_tag] : boundary) {
    const int tag = std::abs(signed_tag);
    std::vector<Curve> p = pieces_of(tag, curve_name(tag), scale);
    if (signed_tag < 0) p = mf::geometry::reversed(std::move(p));
    pieces.insert(pieces.end(), p.begin(), p.end());
  }
  return chain(pieces, tol, error);
}

void read_outline(const outline::Request& q, outline::Result& r) {
  gmsh::open(q.path);
  // A mesh file's entities are discrete: parametrised by their mesh, their curves by their nodes.
  gmsh::model::mesh::createGeometry();
  gmsh::vectorpair volumes, surfaces, groups;
  gmsh::model::getEntities(volumes, 3);
  gmsh::model::getEntities(surfaces, 2);
  r.dimension = !volumes.empty() ? 3 : !surfaces.empty() ? 2 : 1;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    r.groups.push_back({dim, name.empty() ? "group" + std::to_string(tag) : name, {}});
  }
  if (r.dimension < 2) { // gmsh reads a file it cannot parse as an empty model
    gmsh::logger::getLastError(r.error);
    if (!r.error.empty()) r.error = "gmsh cannot read it: " + r.error;
  }
  if (r.dimension != 2) return;
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  const double size = std::max(x1 - x0, y1 - y0);
  if (z1 - z0 > 1e-6 * size) { // OpenCASCADE widens its boxes by its tolerance, 1e-7
    r.error = "its surfaces do not lie in one plane z = const (they reach from z = " +
              std::to_string(z0) + " to " + std::to_string(z1) + ")";
    return;
  }
  const double tol = 1e-9 * q.scale * size;
  r.loops = boundary_loops(surfaces, q.scale, tol, r.error);
  for (std::size_t g = 0; g < groups.size() && r.error.empty(); ++g) {
    std::vector<int> tags;
    gmsh::model::getEntitiesForPhysicalGroup(groups[g].first, groups[g].second, tags);
    if (groups[g].first == 1)
      for (int t : tags) r.groups[g].loops.push_back(pieces_of(t, r.groups[g].name, q.scale));
    if (groups[g].first != 2) continue;
    gmsh::vectorpair members;
    for (int t : tags) members.emplace_back(2, t);
    r.groups[g].loops = boundary_loops(members, q.scale, tol, r.error);
  }
}

} // namespace

extern "C" void meshfree_gmsh_read_outline(const outline::Request& q, outline::Result& r) {
  r = outline::Result{};
  in_session(r.error, [&] { read_outline(q, r); });
}
