// The 3D Galerkin analyses of a problem file (model solid_3d with elastic_static or
// elastoplastic_static): material, discretisation, exact solution, body force, conditions on
// named faces and the load schedule. Every key is checked; errors name the key path.
#include "meshfree/core/memory.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/galerkin_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::spec {

namespace {

Vec3 vec3(KeyReader& r, const std::string& key) {
  const std::vector<double> v = r.numbers(key, 3);
  return Vec3(v[0], v[1], v[2]);
}

/// exact: {solution: linear, u0, gradient}, {solution: thick_cylinder, inner_radius,
/// outer_radius, pressure} or {solution: thick_sphere, inner_radius, outer_radius (default
/// infinite: a cavity in an unbounded body), pressure}.
std::optional<verification::ExactSolution3D> read_exact_3d(KeyReader& r) {
  auto e = r.optional_map("exact");
  if (!e) return std::nullopt;
  verification::ExactSolution3D out;
  const std::string solution =
      e->choice("solution", {"linear", "thick_cylinder", "thick_sphere"}, "");
  if (solution == "thick_sphere") {
    verification::ThickSphere c;
    c.a = e->positive("inner_radius");
    c.b = e->positive("outer_radius", std::numeric_limits<double>::infinity());
    if (!(c.b > c.a)) e->error("outer_radius", "must exceed inner_radius");
    c.p = e->number("pressure");
    out = c;
  } else if (solution == "linear") {
    verification::LinearField3D f;
    f.u0 = vec3(*e, "u0");
    const auto g = e->number_lists("gradient", 3);
    if (g.size() != 3) e->error("gradient", "expected three rows [dui/dx, dui/dy, dui/dz]");
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) f.G(i, j) = g[i][j];
    out = f;
  } else {
    verification::ThickCylinder c;
    c.a = e->positive("inner_radius");
    c.b = e->positive("outer_radius");
    if (!(c.b > c.a)) e->error("outer_radius", "must exceed inner_radius");
    c.p = e->number("pressure");
    out = c;
  }
  e->finish();
  return out;
}

std::vector<std::string> read_names(KeyReader& r, const std::string& key) {
  std::vector<std::string> names;
  const YAML::Node n = r.raw(key);
  if (n.IsScalar()) return {n.Scalar()};
  if (!n.IsSequence()) r.error(key, "expected a face name or a list of them");
  for (const auto& item : n) {
    if (!item.IsScalar()) r.error(key, "expected a list of face names");
    names.push_back(item.Scalar());
  }
  return names;
}

/// displacement: exact | {x, y, z, exact: components}.
void read_held_components(KeyReader& bc, FaceCondition& c) {
  c.constrains = true;
  const YAML::Node n = bc.raw("displacement");
  if (n.IsScalar() && n.Scalar() == "exact") {
    c.value_from_exact = true;
    c.mask = Vec3(1.0, 1.0, 1.0);
    return;
  }
  KeyReader u(n, bc.path_of("displacement"));
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a)
    if (u.has(axes[a])) c.mask(a) = 1.0, c.value(a) = u.number(axes[a]);
  if (u.has("exact")) {
    if (!c.mask.isZero()) u.error("exact", "give either prescribed values (x, y, z) or 'exact'");
    const std::string comps = u.text("exact");
    if (comps.empty() || comps.find_first_not_of("xyz") != std::string::npos)
      u.error("exact", "expected the components held at the exact solution, e.g. 'xz', got '" +
                           one_line(comps) + "'");
    c.value_from_exact = true;
    for (int a = 0; a < 3; ++a) c.mask(a) = comps.find(axes[a][0]) != std::string::npos;
  }
  u.finish();
  if (c.mask.isZero()) bc.error("displacement", "hold at least one of x, y, z (or say 'exact')");
}

/// The faces `name` selects (Prism::names_selected); refused, with the body's faces and the
/// axis sides, where it selects none.
std::vector<std::string> faces_selected(KeyReader& r, const std::string& key,
                                        const std::string& name, const geometry::Prism& body) {
  std::vector<std::string> named = body.names_selected(name);
  if (named.empty()) {
    // The first 12 names: a polygon of many edges must not make the message a page long.
    const std::vector<std::string> faces = body.face_names();
    std::string list;
    for (std::size_t k = 0; k < std::min<std::size_t>(faces.size(), 12); ++k)
      list += (list.empty() ? "" : ", ") + one_line(faces[k], 30);
    if (faces.size() > 12) list += ", ... (" + std::to_string(faces.size()) + " faces)";
    r.error(key, "no face is named '" + one_line(name) + "' (the body's faces: " + list +
                     "; x_min, x_max, y_min, y_max, z_min and z_max name the faces on the sides "
                     "of its bounding box)");
  }
  return named;
}

/// One boundary entry: {name, faces, box, displacement | traction | pressure, penalty}.
FaceCondition read_face_condition(KeyReader& bc, const geometry::Prism& body, double stiffness) {
  FaceCondition c;
  c.key_path = bc.path();
  c.name = bc.text("name");
  check_name(bc, "name", c.name, false);
  if (!bc.has("faces")) bc.error("faces", "name the faces the condition acts on");
  for (const std::string& f : read_names(bc, "faces"))
    for (std::string& named : faces_selected(bc, "faces", f, body))
      if (std::find(c.faces.begin(), c.faces.end(), named) == c.faces.end())
        c.faces.push_back(std::move(named));
  if (bc.has("box")) c.box = read_box(bc, "box", 3);
  const int kinds = bc.has("displacement") + bc.has("traction") + bc.has("pressure");
  if (kinds != 1)
    bc.error("name", "a boundary condition needs exactly one of 'displacement', 'traction' or "
                     "'pressure'");
  if (bc.has("displacement")) {
    read_held_components(bc, c);
    if (bc.has("penalty") && bc.has("penalty_scale"))
      bc.error("penalty_scale", "give either 'penalty' (absolute) or 'penalty_scale' (times E/h)");
    c.penalty =
        bc.has("penalty") ? bc.positive("penalty") : bc.positive("penalty_scale", 1e6) * stiffness;
  } else if (bc.has("traction")) {
    c.loads = true;
    const YAML::Node n = bc.raw("traction");
    if (n.IsScalar() && n.Scalar() == "exact")
      c.traction_from_exact = true;
    else
      c.traction = vec3(bc, "traction");
  } else {
    c.loads = c.pressure_load = true;
    c.pressure = bc.number("pressure");
  }
  for (const char* key : {"penalty", "penalty_scale"})
    if (!c.constrains && bc.has(key)) bc.error(key, "a penalty needs a 'displacement' condition");
  for (const char* key : {"displacement", "traction", "penalty", "penalty_scale"}) bc.allow(key);
  bc.finish();
  return c;
}

/// True when some point of the named faces lies in `box` (the faces sampled: 256 points along
/// each side piece at each of 17 heights, a 64 x 64 lattice over the ends, and 65 latitudes of
/// 128 points over a sphere).
bool faces_meet_box(const geometry::Prism& body, const std::vector<std::string>& faces,
                    const Box& box) {
  const auto named = [&](const std::string& n) {
    return std::find(faces.begin(), faces.end(), n) != faces.end();
  };
  const double tol = 1e-9 * std::max(body.depth, body.section.bounds().size().maxCoeff());
  for (const geometry::Curve& c : body.section.boundary()) {
    if (!named(c.name)) continue;
    for (int i = 0; i <= 256; ++i)
      for (int k = 0; k <= 16; ++k) {
        const Vec2 x = c.point(i / 256.0);
        if (box.contains(Point(x.x(), x.y(), body.z0 + body.depth * k / 16.0), tol)) return true;
      }
  }
  for (const geometry::Sphere& s : body.spheres) {
    if (!named(s.name)) continue;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= 64; ++i)
      for (int j = 0; j < 128; ++j) {
        const double theta = pi * i / 64.0, phi = pi * j / 64.0;
        const Vec3 x = s.center + s.radius * Vec3(std::sin(theta) * std::cos(phi),
                                                  std::sin(theta) * std::sin(phi), std::cos(theta));
        if (body.contains(x, 1e-9) && box.contains(x, tol)) return true;
      }
  }
  const BoundingBox b = body.section.bounds();
  for (const bool back : {true, false}) {
    if (!named(back ? "back" : "front")) continue;
    for (int i = 0; i <= 64; ++i)
      for (int j = 0; j <= 64; ++j) {
        const Vec2 x = b.lo + Vec2(b.size().x() * i / 64.0, b.size().y() * j / 64.0);
        const Point at(x.x(), x.y(), back ? body.z0 : body.z1());
        if (body.section.contains(x) && box.contains(at, tol)) return true;
      }
  }
  return false;
}

void read_boundary(KeyReader& r, const ProblemSpec& p, SolidSpec& s) {
  const geometry::Prism body = s.body(p.domain);
  const double stiffness = p.elasticity().E / s.discretisation.spacing;
  for (KeyReader& bc : r.map_list("boundary")) {
    s.boundary.push_back(read_face_condition(bc, body, stiffness));
    const FaceCondition& c = s.boundary.back();
    for (std::size_t k = 0; k + 1 < s.boundary.size(); ++k)
      if (s.boundary[k].name == c.name)
        bc.error("name", "'" + c.name + "' is used by " + s.boundary[k].key_path + " already");
    if (c.box && !faces_meet_box(body, c.faces, *c.box))
      fail(c.key_path, ".box: holds no point of the faces it selects");
    if ((c.value_from_exact || c.traction_from_exact) && !s.exact)
      bc.error(c.constrains ? "displacement" : "traction",
               "'exact' needs an 'exact' section in the problem");
  }
  if (std::none_of(s.boundary.begin(), s.boundary.end(),
                   [](const FaceCondition& c) { return c.constrains; }))
    r.error("boundary", "no displacement condition: the body is free to move as a rigid body");
}

/// The nodes a refinement box adds along its range of the depth, which it must meet.
double refined_nodes(const geometry::Refinement& r, const SolidSpec& s, const std::string& key) {
  const double lo = std::max(r.z_lo, s.z0), hi = std::min(r.z_hi, s.z0 + s.depth);
  if (hi < lo)
    fail(key, ": its range along z, [", r.z_lo, ", ", r.z_hi, "], misses the body's, [", s.z0, ", ",
         s.z0 + s.depth, "]: it refines nothing");
  const Vec2 extent = r.box.size();
  return (extent.x() / r.spacing + 1.0) * (extent.y() / r.spacing + 1.0) *
         ((hi - lo) / (r.along_z ? r.spacing : s.discretisation.spacing) + 1.0);
}

/// The 3D discretisation: meshfree reproducing kernels or bricks; the plane node count times the
/// layers along z (four times that for 20-node bricks: a corner and three edge midpoints per
/// lattice point) checked against the memory.
void read_solid_discretisation(KeyReader& r, const ProblemSpec& p, const std::string& base_dir,
                               SolidSpec& s) {
  s.discretisation = read_discretisation(r, 3, p.domain.bounds(), base_dir, s.linear_solver);
  DiscretisationSpec& d = s.discretisation;
  const std::string key = "discretisation";
  if (d.method == Method::Fem && d.fem.element == "t3")
    fail(key, ".fem.element: model solid_3d extrudes hex8 or hex20 bricks (q4 or q8 plane "
              "elements), or meshes tet4 or tet10, not t3");
  d.fem.element = solid_element(d.fem.element);
  const bool tets = d.fem.element == "tet4" || d.fem.element == "tet10";
  if (d.method == Method::Fem && !tets && !s.spheres.empty())
    fail("geometry.spheres: bricks extrude a plane mesh and cannot follow the sphere '",
         s.spheres.front().name,
         "'; give discretisation.fem.element tet4 or tet10, or method "
         "meshfree");
  if (d.method == Method::Fem && tets && !d.fem.mesh.empty())
    fail(key, ".fem.mesh: ", d.fem.element,
         " elements are meshed by gmsh from the geometry; a "
         "plane mesh file is extruded into bricks (element q4 or q8)");
  // One point cannot see a quadratic displacement's strains: the stiffness would be singular.
  if (d.method == Method::Fem && d.fem.element == "tet10" && d.fem.order == 1)
    fail(key, ".fem.order: 1 (the centroid) leaves tet10 elements without stiffness against "
              "some displacements; give 2 (4 points, the default) or more");
  if (d.shape.approximation != kernels::Approximation::ReproducingKernel)
    fail(key, ".approximation: model solid_3d takes rk");
  if (s.depth < d.spacing)
    fail(key, ".spacing: ", d.spacing, " exceeds the body's depth along z (", s.depth, ")");
  const Vec2 size = p.domain.bounds().size();
  const bool bricks = d.method == Method::Fem;
  double nodes = (bricks && d.fem.element == "hex20" ? 4.0 : 1.0) * (size.x() / d.spacing + 1.0) *
                 (size.y() / d.spacing + 1.0) * (s.depth / d.spacing + 1.0);
  for (std::size_t i = 0; i < d.refinement.size(); ++i)
    nodes += refined_nodes(d.refinement[i], s, detail::concat(key, ".refinement[", i, "].box"));
  require_memory(key + ".spacing", "nodes over the 3D body", nodes,
                 bytes_per::solid_node(bricks, s.linear_solver.multigrid_for(3.0 * nodes)));
}

/// One output.lines entry: a sampled segment with at least one sample point in the body.
SolidLineSpec read_solid_line(KeyReader& l, const geometry::Prism& body,
                              const std::vector<SolidLineSpec>& earlier) {
  SolidLineSpec s;
  s.name = l.text("name");
  s.from = vec3(l, "from");
  s.to = vec3(l, "to");
  s.points = l.integer("points", 51, 2, 1000000);
  check_name(l, "name", s.name, false);
  for (const auto& other : earlier)
    if (other.name == s.name) l.error("name", "another line is named '" + s.name + "'");
  bool inside = false;
  for (int k = 0; k < s.points && !inside; ++k)
    inside =
        body.contains(s.from + (s.to - s.from) * (static_cast<double>(k) / (s.points - 1)), 1e-9);
  if (!inside) l.error("from", "no sample point of the line lies in the body");
  l.finish();
  return s;
}

/// One output.faces entry: {name, face | box (flat), spacing (default the discretisation's)},
/// at least one sample point in the body and at most a million.
SolidFaceSampleSpec read_face_sample(KeyReader& f, const geometry::Prism& body, double spacing,
                                     const std::vector<SolidFaceSampleSpec>& earlier) {
  SolidFaceSampleSpec s;
  s.name = f.text("name");
  check_name(f, "name", s.name, false);
  for (const auto& other : earlier)
    if (other.name == s.name) f.error("name", "another face sample is named '" + s.name + "'");
  if (f.has("face") == f.has("box")) f.error("name", "give exactly one of 'face' or 'box'");
  s.spacing = f.positive("spacing", spacing);
  if (f.has("face")) {
    const std::string face = f.text("face");
    const std::vector<std::string> named = faces_selected(f, "face", face, body);
    if (named.size() > 1)
      f.error("face", "'" + one_line(face) + "' is " + std::to_string(named.size()) +
                          " faces; a face sample takes one (or a flat box)");
    s.face = named.front();
  } else {
    s.box = read_box(f, "box", 3);
    if ((s.box->hi - s.box->lo).minCoeff() > 1e-12 * body.size())
      f.error("box", "a face sample's box is flat: give one extent zero (lo and hi equal on one "
                     "axis)");
  }
  if (body.size() / s.spacing > 1000.0)
    f.error("spacing", detail::concat(s.spacing,
                                      ": about a million sample points or more (the "
                                      "body's size is ",
                                      body.size(), ")"));
  const std::vector<Vec3> x =
      s.box ? geometry::plane_sample_points(body, s.box->lo, s.box->hi, s.spacing)
            : geometry::face_sample_points(body, s.face, s.spacing);
  if (x.empty()) f.error(s.box ? "box" : "face", "no sample point lies in the body");
  f.finish();
  return s;
}

} // namespace

void parse_solid(KeyReader& r, ProblemSpec& p, const std::string& base_dir) {
  SolidSpec& s = p.solid();
  const bool plastic = p.analysis == Analysis::ElastoplasticStatic;
  const std::string analysis = plastic ? "elastoplastic_static" : "elastic_static";
  s.material_index = take_material(r, p, analysis);
  const MaterialSpec& m = p.materials[s.material_index];
  // The preload stage of a staged run may be elastic (as a plane one may).
  if (plastic && !m.plasticity && p.stage.empty())
    material_error(m, "plasticity", "analysis elastoplastic_static needs a plasticity law");
  if (!plastic && m.plasticity)
    material_error(m, "plasticity", "used only by analysis elastoplastic_static");
  // the explicit stage's particles fill the body's box: they would fill a spherical hole too
  if (!p.stage.empty() && !s.spheres.empty())
    fail("geometry.spheres: a staged run's particles do not leave out spherical holes; run the "
         "body with spheres as its own elastic_static or elastoplastic_static analysis");
  s.linear_solver = read_linear_solver(r);
  read_solid_discretisation(r, p, base_dir, s);
  s.exact = read_exact_3d(r);
  if (r.has("body_force")) s.body_force = vec3(r, "body_force");
  r.allow("body_force");
  read_boundary(r, p, s);
  if (auto out = r.optional_map("output")) {
    s.gauges = read_gauges(*out, 3);
    if (!plastic && out->has("fields_every"))
      out->error("fields_every", "an elastic run writes one frame; fields_every is for "
                                 "analysis elastoplastic_static");
    s.fields_every = out->integer("fields_every", 1, 1, 1000000);
    const geometry::Prism body = s.body(p.domain);
    for (std::size_t k = 0; k < s.gauges.size(); ++k)
      if (!body.contains(s.gauges[k].at, 1e-9))
        fail(out->path_of("gauges"), "[", k, "].at: the point (",
             detail::concat(s.gauges[k].at.x(), ", ", s.gauges[k].at.y(), ", ", s.gauges[k].at.z()),
             ") is not in the body");
    for (KeyReader& l : out->map_list("lines"))
      s.lines.push_back(read_solid_line(l, body, s.lines));
    for (KeyReader& f : out->map_list("faces"))
      s.faces.push_back(read_face_sample(f, body, s.discretisation.spacing, s.faces));
    out->finish();
  }
  if (plastic) {
    std::vector<std::string> names;
    for (const FaceCondition& c : s.boundary) names.push_back(c.name);
    s.steps = read_steps(r, names, false);
    s.nonlinear = read_nonlinear(r);
  } else {
    for (const char* key : {"steps", "nonlinear"})
      if (r.has(key)) r.error(key, "used only by analysis elastoplastic_static");
  }
}

} // namespace mf::spec
