// Closed loops of segments and arcs: the outline and the holes of a body read from a file. A
// loop is its chords' polygon with a cap (the circular segment between chord and arc) added at
// each arc that bulges out of it and taken away at each that bulges in; no arc sweeps more than
// a half turn, so that every cap is the smaller segment of its circle, and caps do not overlap
// (the segment's area: [Zwillinger 2018], docs/references.md).
#include "meshfree/core/error.hpp"
#include "meshfree/geometry/domain.hpp"
#include <algorithm>
#include <cmath>

namespace mf::geometry {

namespace {

double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

/// True for points between an arc and its chord, the chord included (to 1e-12 of its length: a
/// point on it may carry rounding off either side).
bool in_cap(const Curve& arc, const Vec2& p) {
  if ((p - arc.center).norm() >= arc.radius) return false;
  const Vec2 a = arc.point(0.0), chord = arc.point(1.0) - a;
  const double side = cross(chord, arc.point(0.5) - a) > 0.0 ? 1.0 : -1.0;
  return side * cross(chord, p - a) >= -1e-12 * chord.squaredNorm();
}

double cap_area(const Curve& arc) {
  const double phi = arc.theta1 - arc.theta0; // signed: a counter-clockwise arc adds
  return 0.5 * arc.radius * arc.radius * (phi - std::sin(phi));
}

std::vector<Vec2> chords(const std::vector<Curve>& loop) {
  std::vector<Vec2> v;
  for (const Curve& c : loop) v.push_back(c.point(0.0));
  return v;
}

} // namespace

std::vector<Curve> close_loop(std::vector<Curve> loop, bool clockwise, double tol) {
  MF_REQUIRE(!loop.empty(), "a loop needs at least one piece");
  const double pi = std::acos(-1.0);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Curve& c = loop[i];
    const Vec2 end = c.point(1.0), next = loop[(i + 1) % loop.size()].point(0.0);
    MF_REQUIRE((end - next).norm() <= tol, "the loop is open: its piece '", c.name, "' ends at (",
               end.x(), ", ", end.y(), "), the next starts at (", next.x(), ", ", next.y(), ")");
    MF_REQUIRE(c.kind == Curve::Kind::Segment || std::abs(c.theta1 - c.theta0) <= pi * (1 + 1e-12),
               "the arc '", c.name, "' sweeps more than a half turn");
  }
  const double area = loop_area(loop);
  MF_REQUIRE(std::abs(area) > 0.0, "the loop encloses no area");
  return (area < 0.0) == clockwise ? loop : reversed(std::move(loop));
}

double loop_area(const std::vector<Curve>& loop) {
  double area = signed_area(chords(loop));
  for (const Curve& c : loop)
    if (c.kind == Curve::Kind::Arc) area += cap_area(c);
  return area;
}

bool inside_loop(const std::vector<Curve>& loop, const Vec2& p) {
  // A cap is enclosed where its arc runs in the loop's sense (the enclosed side of both is
  // then the circle's inside); deciding there, not by the polygon, keeps points on a chord right.
  for (const Curve& c : loop)
    if (c.kind == Curve::Kind::Arc && in_cap(c, p))
      return (c.theta1 > c.theta0) == (loop_area(loop) > 0.0);
  return inside_polygon(chords(loop), p);
}

BoundingBox loop_bounds(const std::vector<Curve>& loop) {
  BoundingBox bb{loop[0].point(0.0), loop[0].point(0.0)};
  const auto add = [&](const Vec2& v) {
    bb.lo = bb.lo.cwiseMin(v);
    bb.hi = bb.hi.cwiseMax(v);
  };
  for (const Curve& c : loop) { // the pieces' ends, and the arcs' extreme points
    add(c.point(1.0));
    if (c.kind != Curve::Kind::Arc) continue;
    for (const Vec2& u : {Vec2(1.0, 0.0), Vec2(0.0, 1.0), Vec2(-1.0, 0.0), Vec2(0.0, -1.0)})
      if (c.distance_to(c.center + c.radius * u) <= 1e-12 * c.radius) add(c.center + c.radius * u);
  }
  return bb;
}

Domain Domain::from_loops(std::vector<Curve> outline, std::vector<std::vector<Curve>> holes) {
  MF_REQUIRE(!outline.empty(), "the body's outline has no piece");
  BoundingBox bb = loop_bounds(outline);
  const double tol = 1e-9 * bb.size().maxCoeff();
  Domain d;
  d.outline_ = close_loop(std::move(outline), false, tol);
  MF_REQUIRE(d.outline_.size() >= 2, "the body's outline needs at least two pieces");
  for (const Curve& c : d.outline_) {
    d.vertices_.push_back(c.point(0.0));
    d.edge_names_.push_back(c.name);
    if (c.kind == Curve::Kind::Arc) d.arcs_.push_back(c);
  }
  d.scale_ = bb.size().maxCoeff();
  for (std::vector<Curve>& h : holes) d.add_hole(OutlineHole::loop_of(std::move(h)));
  return d;
}

OutlineHole OutlineHole::loop_of(std::vector<Curve> pieces) {
  MF_REQUIRE(!pieces.empty(), "a hole's loop has no piece");
  const BoundingBox bb = loop_bounds(pieces);
  OutlineHole h;
  h.kind = Kind::Loop;
  h.curves = close_loop(std::move(pieces), true, 1e-9 * bb.size().maxCoeff());
  MF_REQUIRE(h.curves.size() >= 2, "a hole's loop needs at least two pieces");
  h.name = h.curves.front().name;
  return h;
}

} // namespace mf::geometry
