// The geometry of a 2D body in a problem file (a rectangle, a polygon or a geometry file's body,
// its corners rounded or not, with holes: circles, polygons, rectangles, slots) and the pieces of
// its boundary a condition names. Every key is checked; errors name the key path.
#include "meshfree/geometry/outline_file.hpp"
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>

namespace mf::spec {

namespace {

/// One entry of `holes`: a circle (`center`, `radius`) or an outline (read_outline_hole), with
/// an optional name; refused where it misses the body or leaves nothing of its outline.
void add_hole(KeyReader& h, geometry::Domain& d) {
  const char* const kinds[] = {"center", "polygon", "rectangle", "slot"};
  const int given = static_cast<int>(
      std::count_if(std::begin(kinds), std::end(kinds), [&](const char* k) { return h.has(k); }));
  if (given != 1)
    h.error(given ? "center" : "radius",
            "give one of a circle (center and radius), a polygon, a rectangle or a slot");
  const std::string name = h.text("name", "");
  check_name(h, "name", name, true);
  const bool circle = h.has("center");
  if (circle)
    d.add_hole(geometry::Circle{h.vec2("center"), h.positive("radius"), name});
  else
    d.add_hole(*read_outline_hole(h, name));
  h.finish();
  const std::string key = circle ? "radius"
                                 : (h.has("slot")      ? "slot"
                                    : h.has("polygon") ? "polygon"
                                                       : "rectangle");
  bool outline_left = false;
  for (const auto& piece : d.boundary())
    outline_left = outline_left || piece.kind == geometry::Curve::Kind::Segment;
  if (!outline_left) h.error(key, "the hole covers the whole body");
  const std::string& made = circle ? d.holes().back().name : d.outline_holes().back().name;
  bool cuts = false;
  for (const auto& piece : d.boundary()) cuts = cuts || piece.name == made;
  if (!cuts) h.error(circle ? "center" : key, "the hole '" + made + "' does not cut the body");
}

/// One entry of `fillets`: the corner at `at` rounded with `radius`, with an optional name.
void round_corner(KeyReader& f, geometry::Domain& d) {
  const Vec2 at = f.vec2("at");
  const double radius = f.positive("radius");
  const std::string name = f.text("name", "");
  check_name(f, "name", name, true);
  f.finish();
  try {
    d.round_corner(at, radius, name);
  } catch (const Error& e) {
    const std::string why = e.what();
    f.error(why.find("radius") != std::string::npos || why.find("needs") != std::string::npos
                ? "radius"
                : "at",
            why);
  }
}

} // namespace

geometry::OutlineFile read_geometry_file(KeyReader& g, const std::string& base_dir) {
  const std::string file = g.text("file");
  const std::string path = !file.empty() && file.front() == '/' ? file : base_dir + file;
  const double scale = g.positive("scale", 1.0);
  try {
    return geometry::read_outline_file(path, scale);
  } catch (const Error& e) {
    fail(g.path_of("file"), ": ", e.what());
  }
}

const geometry::FilePart& file_part(KeyReader& r, const std::vector<geometry::FilePart>& parts) {
  const std::string group = r.text("group");
  std::string known;
  for (const geometry::FilePart& f : parts) {
    if (f.name == group) return f;
    known += (known.empty() ? "" : ", ") + f.name;
  }
  r.error("group", "the geometry file has no group of surfaces named '" + one_line(group) +
                       "' (its groups: " + (known.empty() ? "none" : known) + ")");
}

std::vector<PartMaterial> read_part_materials(KeyReader& r, const ProblemSpec& p) {
  if (!r.has("parts")) return {};
  if (p.file_parts.empty())
    r.error("parts", "names the groups of surfaces of a geometry file (geometry.file), and the "
                     "body has none");
  std::vector<PartMaterial> out;
  std::vector<std::string> given;
  for (KeyReader& g : r.map_list("parts")) {
    const geometry::FilePart& part = file_part(g, p.file_parts);
    if (std::find(given.begin(), given.end(), part.name) != given.end())
      g.error("group", "'" + part.name + "' is given a material already");
    given.push_back(part.name);
    out.push_back({g.path(), &part, find_material(g, "material", p.materials, g.text("material"))});
    g.finish();
  }
  for (const geometry::FilePart& f : p.file_parts)
    if (std::find(given.begin(), given.end(), f.name) == given.end())
      r.error("parts", "the geometry file's group of surfaces '" + f.name +
                           "' has no material: give {group: " + f.name + ", material: ...}");
  // Every point of the body in one part: the parts' areas add up to the body's.
  double covered = 0.0;
  for (const geometry::FilePart& f : p.file_parts) covered += geometry::file_body_area(f.body);
  const double whole = geometry::file_body_area(p.domain);
  if (std::abs(covered - whole) > 1e-9 * whole)
    r.error("parts",
            detail::concat("the geometry file's groups of surfaces cover an area of ", covered,
                           ", the body ", whole, ": every surface needs one group (and one only)"));
  return out;
}

geometry::Domain read_domain(KeyReader& g, const std::string& base_dir, ProblemSpec* p) {
  const int given = g.has("rectangle") + g.has("polygon") + g.has("file");
  if (given != 1) g.error("rectangle", "give exactly one of 'rectangle', 'polygon' or 'file'");
  const bool rect = g.has("rectangle");
  geometry::Domain d = geometry::Domain::rectangle({0, 0}, {1, 1});
  if (g.has("file")) {
    geometry::OutlineFile read = read_geometry_file(g, base_dir);
    d = std::move(read.body);
    if (p) {
      p->file_parts = std::move(read.parts);
      p->file_curves = std::move(read.curves);
    }
  } else if (rect) {
    KeyReader rr = g.map("rectangle");
    const Vec2 origin = rr.has("origin") ? rr.vec2("origin") : Vec2(0.0, 0.0);
    rr.allow("origin");
    const Vec2 size = rr.vec2("size");
    if (!(size.x() > 0.0 && size.y() > 0.0)) rr.error("size", "expected positive width and height");
    // Coordinates carry 16 digits: a body far from 0 against its size loses its shape.
    if (origin.cwiseAbs().maxCoeff() * 1e-9 > size.minCoeff())
      rr.error("origin", "lies too far from 0 for a body of this size (more than 1e9 times its "
                         "smallest side): place the body nearer the origin");
    rr.finish();
    d = geometry::Domain::rectangle(origin, size);
  } else {
    KeyReader pr = g.map("polygon");
    std::vector<Vec2> v = pr.vec2_list("vertices");
    std::vector<std::string> names;
    if (pr.has("edge_names")) {
      YAML::Node n = pr.raw("edge_names");
      if (!n.IsSequence() || n.size() != v.size())
        pr.error("edge_names", "expected a list of " + std::to_string(v.size()) + " names");
      for (const auto& e : n) {
        if (!e.IsScalar()) pr.error("edge_names", "expected a list of names");
        names.push_back(e.Scalar());
      }
    }
    pr.allow("edge_names");
    pr.finish();
    try {
      d = geometry::Domain::polygon(v, names);
    } catch (const Error& e) {
      fail(pr.path_of("vertices"), ": ", e.what());
    }
  }
  for (KeyReader& f : g.map_list("fillets")) round_corner(f, d);
  for (KeyReader& h : g.map_list("holes")) add_hole(h, d);
  g.finish();
  return d;
}

std::vector<geometry::Curve> select_boundary(const geometry::Domain& domain, const Region& on,
                                             const std::string& key_path) {
  std::vector<geometry::Curve> out;
  const auto all = domain.boundary();
  std::vector<std::string> edges;
  for (const auto& name : on.edges) {
    const std::vector<std::string> named = domain.names_selected(name);
    if (named.empty()) {
      std::string names;
      for (const auto& c : all)
        if (names.find(c.name) == std::string::npos) names += (names.empty() ? "" : ", ") + c.name;
      fail(key_path, ".edges: no boundary piece is named '", one_line(name),
           "' (the body's pieces: ", names,
           "; x_min, x_max, y_min and y_max name the edges on the sides of its bounding box)");
    }
    edges.insert(edges.end(), named.begin(), named.end());
  }
  for (const auto& c : all) {
    const bool named =
        on.edges.empty() || std::find(edges.begin(), edges.end(), c.name) != edges.end();
    if (!named) continue;
    if (!on.box) {
      out.push_back(c);
      continue;
    }
    const double tol = 1e-9 * (domain.bounds().size().maxCoeff());
    for (const auto& [t0, t1] : geometry::kept_intervals(
             c, [&](const Vec2& p) { return on.box->contains(Point(p.x(), p.y(), 0.0), tol); }))
      out.push_back(c.piece(t0, t1));
  }
  double length = 0.0;
  for (const auto& c : out) length += c.length();
  if (out.empty() || length <= 0.0) fail(key_path, ": selects no part of the boundary");
  return out;
}

} // namespace mf::spec
