// The front of a problem file, shared by every analysis: name, description, units, analysis,
// model, materials and geometry; then the reader of the analysis for the rest. A file may list
// `stages:` instead of one analysis.
#include "meshfree/core/input_file.hpp"
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>
#include <cmath>
#include <fstream>

namespace mf::spec {

namespace {

const std::vector<std::string> kAnalyses{"elastic_static", "elastoplastic_static",
                                         "model_problem_1d", "peridynamics", "sph"};

Analysis analysis_of(const std::string& name) {
  return name == "elastic_static"         ? Analysis::ElasticStatic
         : name == "elastoplastic_static" ? Analysis::ElastoplasticStatic
         : name == "peridynamics"         ? Analysis::Peridynamics
         : name == "sph"                  ? Analysis::Sph
                                          : Analysis::ModelProblem1D;
}

void read_model(KeyReader& r, ProblemSpec& p) {
  KeyReader m = r.map("model");
  const std::string type =
      m.choice("type", {"plane_stress", "plane_strain", "solid_3d", "uniaxial_strain"}, "");
  p.model_type = type == "plane_stress"   ? ModelType::PlaneStress
                 : type == "plane_strain" ? ModelType::PlaneStrain
                 : type == "solid_3d"     ? ModelType::Solid3D
                                          : ModelType::UniaxialStrain;
  p.dimension = p.model_type == ModelType::Solid3D          ? 3
                : p.model_type == ModelType::UniaxialStrain ? 1
                                                            : 2;
  p.model = p.model_type == ModelType::PlaneStrain ? materials::PlaneModel::PlaneStrain
                                                   : materials::PlaneModel::PlaneStress;
  p.thickness = m.positive("thickness", 1.0);
  if (p.dimension != 2 && m.has("thickness"))
    m.error("thickness", "only a plane model has a thickness");
  m.finish();
}

bool galerkin(Analysis a) {
  return a == Analysis::ElasticStatic || a == Analysis::ElastoplasticStatic;
}

/// geometry.box: {origin, size} of a 3D body; the geometry map holds nothing else.
Box read_body_box(KeyReader& g) {
  KeyReader b = g.map("box");
  const Point origin = b.has("origin") ? read_point(b, "origin", 3) : Point(0, 0, 0);
  b.allow("origin");
  const Point size = read_point(b, "size", 3);
  if (size.minCoeff() <= 0.0) b.error("size", "expected positive extents");
  b.finish();
  g.finish();
  return Box{origin, origin + size};
}

/// True when some point of the sphere's surface (a 64 x 32 latitude-longitude sample) lies in
/// the body's interior: the sphere cuts the body.
bool sphere_cuts(const geometry::Prism& body, const geometry::Sphere& s) {
  const double pi = 3.14159265358979323846, tol = 1e-9 * body.size();
  for (int i = 1; i < 32; ++i)
    for (int j = 0; j < 64; ++j) {
      const double theta = pi * i / 32.0, phi = 2.0 * pi * j / 64.0;
      const Vec3 x = s.center + s.radius * Vec3(std::sin(theta) * std::cos(phi),
                                                std::sin(theta) * std::sin(phi), std::cos(theta));
      const Vec2 xy = x.head<2>();
      if (x.z() > body.z0 + tol && x.z() < body.z1() - tol && body.section.contains(xy) &&
          body.section.distance_to_outline(xy) > tol && body.outside_spheres(x, 1e-9))
        return true;
    }
  return false;
}

/// geometry.spheres: each a spherical hole {center, radius, name} that cuts the body and meets
/// no other hole (sphere or cylinder); its name (default sphere<i>) is a face name of its own.
void read_spheres(std::vector<KeyReader>& list, const geometry::Domain& section, SolidSpec& solid) {
  for (KeyReader& h : list) {
    geometry::Sphere s;
    s.center = read_point(h, "center", 3);
    s.radius = h.positive("radius");
    s.name = h.text("name", "sphere" + std::to_string(solid.spheres.size()));
    check_name(h, "name", s.name, false);
    h.finish();
    const geometry::Prism body = solid.body(section);
    const std::vector<std::string> names = body.face_names();
    if (std::find(names.begin(), names.end(), s.name) != names.end())
      h.error("name", "'" + s.name + "' already names a face of the body");
    for (const geometry::Sphere& o : solid.spheres)
      if ((o.center - s.center).norm() < o.radius + s.radius)
        h.error("radius", detail::concat(s.radius, ": the sphere '", s.name,
                                         "' overlaps the sphere '", o.name, "'"));
    for (const geometry::Circle& c : section.holes())
      if ((c.center - s.center.head<2>()).norm() < c.radius + s.radius &&
          s.center.z() + s.radius > solid.z0 && s.center.z() - s.radius < solid.z0 + solid.depth)
        h.error("radius", detail::concat(s.radius, ": the sphere '", s.name,
                                         "' overlaps the cylindrical hole '", c.name, "'"));
    for (const geometry::OutlineHole& o : section.outline_holes())
      if ((o.contains(s.center.head<2>()) || o.distance_to(s.center.head<2>()) < s.radius) &&
          s.center.z() + s.radius > solid.z0 && s.center.z() - s.radius < solid.z0 + solid.depth)
        h.error("radius", detail::concat(s.radius, ": the sphere '", s.name,
                                         "' overlaps the hole '", o.name, "'"));
    if (!sphere_cuts(body, s))
      h.error("center", detail::concat("[", s.center.x(), ", ", s.center.y(), ", ", s.center.z(),
                                       "]: the sphere '", s.name, "' does not cut the body"));
    solid.spheres.push_back(s);
  }
}

/// geometry of a 3D Galerkin body: a box {origin, size}, or a plane body (rectangle or polygon,
/// with holes) and `extrude: {z0, depth}`; both are prisms along z (geometry::Prism), minus the
/// `spheres: [{center, radius, name}]` (read_spheres).
void read_solid_geometry(KeyReader& g, ProblemSpec& p) {
  SolidSpec& solid = p.part.emplace<SolidSpec>();
  if (g.has("file"))
    g.error("file", "a 3D body is read from a file by the plane models only so far (model.type "
                    "plane_stress or plane_strain); give a box, or a plane body and extrude");
  std::vector<KeyReader> spheres = g.map_list("spheres");
  if (g.has("box")) {
    p.box = read_body_box(g);
    const Point size = p.box->hi - p.box->lo;
    p.domain = geometry::Domain::rectangle(p.box->lo.head<2>(), size.head<2>());
    solid.z0 = p.box->lo.z();
    solid.depth = size.z();
  } else {
    KeyReader e = g.map("extrude");
    solid.z0 = e.number("z0", 0.0);
    solid.depth = e.positive("depth");
    e.finish();
    p.domain = read_domain(g, "");
    const BoundingBox b = p.domain.bounds();
    p.box =
        Box{Point(b.lo.x(), b.lo.y(), solid.z0), Point(b.hi.x(), b.hi.y(), solid.z0 + solid.depth)};
  }
  read_spheres(spheres, p.domain, solid);
}

/// geometry: a 2D body (rectangle or polygon, with holes) or a 3D box {origin, size}.
void read_geometry(KeyReader& r, ProblemSpec& p, const std::string& base_dir) {
  KeyReader g = r.map("geometry");
  if (p.dimension == 3 && galerkin(p.analysis))
    read_solid_geometry(g, p);
  else if (p.dimension == 3)
    p.box = read_body_box(g);
  else
    p.domain = read_domain(g, base_dir, &p);
}

/// Every scalar under `node` as "path = value" (list items by index), in the file's order.
void flatten(const YAML::Node& node, const std::string& path, ProblemSettings& out) {
  if (node.IsMap()) {
    for (const auto& item : node) {
      const std::string key = item.first.IsScalar() ? item.first.Scalar() : "?";
      flatten(item.second, path.empty() ? key : path + "." + key, out);
    }
  } else if (node.IsSequence()) {
    for (std::size_t k = 0; k < node.size(); ++k)
      flatten(node[k], path + "." + std::to_string(k), out);
  } else {
    out.emplace_back(path, node.IsScalar() ? node.Scalar() : std::string("~"));
  }
}

} // namespace

ProblemSpec parse_problem(YAML::Node root, const std::string& base_dir, const std::string& stage) {
  KeyReader r(root, "");
  ProblemSpec p;
  p.stage = stage;
  std::vector<std::string> analyses = kAnalyses;
  analyses.push_back("staged");
  if (r.has("analysis") && r.text("analysis") == "staged") {
    if (!stage.empty()) r.error("analysis", "a stage cannot itself be staged");
    StagedSpec& staged = p.part.emplace<StagedSpec>();
    parse_stages(r, p, base_dir);
    r.finish();
    if (staged.stages.size() == 1) return std::move(staged.stages.front()); // runs as its analysis
    const ProblemSpec& first = staged.stages.front();
    p.name = first.name;
    p.description = first.description;
    p.units = first.units;
    p.analysis = Analysis::Staged;
    p.model_type = first.model_type;
    p.dimension = first.dimension;
    p.model = first.model;
    p.thickness = first.thickness;
    p.materials = first.materials;
    return p;
  }
  p.name = r.text("name");
  check_name(r, "name", p.name);
  p.description = r.text("description", "");
  p.units = r.text("units", "");
  p.analysis = analysis_of(r.choice("analysis", analyses, ""));
  if (p.analysis == Analysis::ModelProblem1D) {
    // A 1D problem: the model, if given, can only be uniaxial.
    if (r.has("model")) {
      read_model(r, p);
      if (p.model_type != ModelType::UniaxialStrain)
        r.error("model", "analysis model_problem_1d takes model.type uniaxial_strain");
    }
    r.allow("model");
    parse_model_1d(r, p, base_dir);
    r.finish();
    return p;
  }
  read_model(r, p);
  p.materials = read_materials(r);
  if (p.analysis == Analysis::Sph) {
    p.part = parse_sph(r, p, base_dir);
  } else {
    read_geometry(r, p, base_dir);
    if (p.analysis == Analysis::Peridynamics)
      p.part = parse_pd(r, p, base_dir);
    else if (p.dimension == 3)
      parse_solid(r, p, base_dir);
    else
      parse_galerkin(r, p, base_dir);
  }
  r.finish();
  return p;
}

ProblemSpec read_problem(const std::string& path, const std::vector<std::string>& overrides) {
  require_regular_file(path, "problem file");
  std::ifstream in(path);
  MF_REQUIRE(in.good(), path, ": cannot open the problem file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    fail(path, ": not valid YAML: ", e.what());
  }
  for (const auto& o : overrides) apply_override(root, o);
  try {
    const std::size_t slash = path.find_last_of('/');
    ProblemSpec spec =
        parse_problem(root, slash == std::string::npos ? "" : path.substr(0, slash + 1));
    flatten(root, "", spec.settings);
    return spec;
  } catch (const YAML::Exception& e) {
    fail(path, ": malformed input: ", e.what());
  }
}

} // namespace mf::spec
