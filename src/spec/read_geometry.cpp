// The geometry of a 2D body in a problem file (a rectangle or a polygon, with circular holes) and
// the pieces of its boundary a condition names. Every key is checked; errors name the key path.
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/spec_read.hpp"

namespace mf::spec {

geometry::Domain read_domain(KeyReader& g) {
  const bool rect = g.has("rectangle"), poly = g.has("polygon");
  if (rect == poly) g.error("rectangle", "give exactly one of 'rectangle' or 'polygon'");
  geometry::Domain d = geometry::Domain::rectangle({0, 0}, {1, 1});
  if (rect) {
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
  for (KeyReader& h : g.map_list("holes")) {
    geometry::Circle c;
    c.center = h.vec2("center");
    c.radius = h.positive("radius");
    c.name = h.text("name", "");
    check_name(h, "name", c.name, true);
    h.finish();
    d.add_hole(c);
    bool outline_left = false;
    for (const auto& piece : d.boundary())
      outline_left = outline_left || piece.kind == geometry::Curve::Kind::Segment;
    if (!outline_left) h.error("radius", "the hole covers the whole body");
    const std::string name = d.holes().back().name;
    bool cuts = false;
    for (const auto& piece : d.boundary()) cuts = cuts || piece.name == name;
    if (!cuts) h.error("center", "the hole '" + name + "' does not cut the body");
  }
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
