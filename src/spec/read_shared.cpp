// Readers shared by every analysis: names, points, boxes, regions, gauges and blasts.
#include "meshfree/spec/spec_read.hpp"
#include <cmath>

namespace mf::spec {

void check_name(KeyReader& r, const std::string& key, const std::string& name, bool may_be_empty) {
  if (name.empty() && may_be_empty) return;
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
          std::string::npos)
    r.error(key, "expected a name of letters, digits, '_' or '-', got '" + one_line(name) + "'");
  // Names become file names (out/<name>, line_<name>.csv, <stage>_fields.h5).
  if (name.size() > 64)
    r.error(key, "a name of at most 64 characters, got " + std::to_string(name.size()));
}

Point read_point(KeyReader& r, const std::string& key, int dim) {
  const std::vector<double> v = r.numbers(key, dim);
  Point p(0, 0, 0);
  for (int d = 0; d < dim; ++d) p(d) = v[d];
  return p;
}

Point read_unit_vector(KeyReader& r, const std::string& key, int dim) {
  Point v = read_point(r, key, dim);
  const double norm = std::sqrt(v.x() * v.x() + v.y() * v.y() + v.z() * v.z());
  if (!(norm > 0.0)) r.error(key, "expected a non-zero vector");
  for (int d = 0; d < 3; ++d) v(d) /= norm;
  return v;
}

Box read_box(KeyReader& r, const std::string& key, int dim) {
  const auto corners = r.number_lists(key, dim);
  if (corners.size() != 2) r.error(key, "expected two corners [[x0, ...], [x1, ...]]");
  Box b;
  for (int d = 0; d < 3; ++d) {
    b.lo(d) = d < dim ? std::min(corners[0][d], corners[1][d]) : -1e300;
    b.hi(d) = d < dim ? std::max(corners[0][d], corners[1][d]) : 1e300;
  }
  return b;
}

namespace {
Circle read_circle(KeyReader& c) {
  Circle out;
  const std::vector<double> at = c.numbers("center", 2);
  out.center = Point(at[0], at[1], 0.0);
  out.radius = c.positive("radius");
  c.finish();
  return out;
}
} // namespace

std::optional<geometry::OutlineHole> read_outline_hole(KeyReader& h, const std::string& name) {
  if (h.has("polygon")) {
    try {
      return geometry::OutlineHole::polygon(h.vec2_list("polygon"), name);
    } catch (const Error& e) {
      fail(h.path_of("polygon"), ": ", e.what());
    }
  }
  if (h.has("rectangle")) {
    KeyReader r = h.map("rectangle");
    const Vec2 origin = r.vec2("origin"), size = r.vec2("size");
    if (!(size.x() > 0.0 && size.y() > 0.0)) r.error("size", "expected positive width and height");
    r.finish();
    return geometry::OutlineHole::polygon(
        {origin, origin + Vec2(size.x(), 0.0), origin + size, origin + Vec2(0.0, size.y())}, name);
  }
  if (!h.has("slot")) return std::nullopt;
  KeyReader r = h.map("slot");
  const Vec2 from = r.vec2("from"), to = r.vec2("to");
  const double width = r.positive("width");
  r.finish();
  return geometry::OutlineHole::slot(from, to, 0.5 * width, name);
}

Region read_region(KeyReader& r, int dim, unsigned shapes) {
  Region g;
  if ((shapes & kBox) && r.has("box")) g.box = read_box(r, "box", dim);
  if (shapes & kBox) r.allow("box");
  if (shapes & kCircle) {
    if (auto c = r.optional_map("circle")) {
      if (dim == 1) c->error("center", "a circle needs 2D or 3D");
      g.circle = read_circle(*c);
    }
  }
  if (shapes & kHoles) {
    for (KeyReader& c : r.map_list("holes")) {
      if (dim == 1) c.error("center", "holes need 2D or 3D");
      if (auto outline = read_outline_hole(c, "")) {
        c.finish();
        g.outline_holes.push_back(*outline);
      } else {
        g.holes.push_back(read_circle(c));
      }
    }
  }
  if (shapes & kRing) {
    if (auto c = r.optional_map("ring")) {
      if (dim != 2) r.error("ring", "rings are available in 2D only");
      Ring ring;
      ring.center = read_point(*c, "center", dim);
      ring.inner_radius = c->positive("inner_radius");
      ring.outer_radius = c->positive("outer_radius");
      if (!(ring.outer_radius > ring.inner_radius))
        c->error("outer_radius", "must exceed inner_radius");
      c->finish();
      g.ring = ring;
    }
  }
  if ((shapes & kEdges) && r.has("edges")) {
    const YAML::Node e = r.raw("edges");
    if (e.IsScalar()) {
      g.edges.push_back(e.Scalar());
    } else {
      if (!e.IsSequence()) r.error("edges", "expected a boundary name or a list of them");
      for (const auto& n : e) {
        if (!n.IsScalar()) r.error("edges", "expected a list of boundary names");
        g.edges.push_back(n.Scalar());
      }
    }
  }
  if (shapes & kEdges) r.allow("edges");
  return g;
}

std::vector<GaugeSpec> read_gauges(KeyReader& output, int dim) {
  std::vector<GaugeSpec> out;
  for (KeyReader& g : output.map_list("gauges")) {
    GaugeSpec gauge;
    gauge.name = g.text("name");
    check_name(g, "name", gauge.name);
    for (const auto& other : out)
      if (other.name == gauge.name) g.error("name", "another gauge is named '" + gauge.name + "'");
    gauge.at = read_point(g, "at", dim);
    g.finish();
    out.push_back(gauge);
  }
  return out;
}

TimeSpec read_time(KeyReader& r, StepControl control) {
  KeyReader t = r.map("time");
  TimeSpec s;
  s.end = t.positive("end");
  if (control == StepControl::Safety) {
    s.dt = t.positive("dt", 0.0);
    s.safety = t.positive("safety", 0.8);
    if (s.safety > 1.0)
      t.error("safety", "expected a safety factor in (0, 1], got " + detail::concat(s.safety));
  } else {
    s.courant = t.positive("courant", 0.3);
    if (s.courant > 1.0) t.error("courant", "expected a Courant number <= 1");
  }
  t.finish();
  return s;
}

SeriesOutputSpec read_series_output(KeyReader& output, int dim) {
  SeriesOutputSpec s;
  s.history_interval = output.positive("history_interval", 0.0);
  s.fields_interval = output.positive("fields_interval", 0.0);
  s.gauges = read_gauges(output, dim);
  s.checkpoint.interval = output.positive("checkpoint_interval", 0.0);
  s.checkpoint.wall_interval = output.number("checkpoint_wall_interval", 600.0);
  if (!(s.checkpoint.wall_interval >= 0.0) || !std::isfinite(s.checkpoint.wall_interval))
    output.error("checkpoint_wall_interval", "expected seconds of wall time, 0 for none, got " +
                                                 detail::concat(s.checkpoint.wall_interval));
  return s;
}

BlastSpec read_blast(KeyReader& b, int dim, bool near_field) {
  BlastSpec out;
  out.tnt_mass = b.positive("tnt_mass");
  out.surface_burst = b.choice("burst", {"surface", "free_air"}, "surface") == "surface";
  out.charge = read_point(b, "charge_at", dim);
  out.normal = read_unit_vector(b, "normal", dim);
  if (near_field)
    out.clamp_below_range = b.choice("near_field", {"error", "clamp"}, "error") == "clamp";
  b.finish();
  return out;
}

} // namespace mf::spec
