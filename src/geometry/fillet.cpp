// Rounded corners of a plane body's outline: the arc tangent to the two edges at a corner
// (the fillet's tangent length r tan(phi / 2) for a turn of phi between the edges; its cap,
// between the corner and the arc, of area r^2 tan(phi / 2) - r^2 phi / 2), and the outline as
// the straight parts of the edges and the arcs between them.
#include "meshfree/core/error.hpp"
#include "meshfree/geometry/domain.hpp"
#include <algorithm>
#include <cmath>

namespace mf::geometry {

namespace {

double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

/// The turn phi in (0, pi) between the directions u and v, and its sense (left: convex on a
/// counter-clockwise outline).
double turn(const Vec2& u, const Vec2& v) {
  return std::atan2(std::abs(cross(u, v)), u.dot(v));
}

} // namespace

Curve Fillet::arc() const {
  Curve c;
  c.kind = Curve::Kind::Arc;
  c.name = name;
  c.center = center;
  c.radius = radius;
  c.theta0 = std::atan2(from.y() - center.y(), from.x() - center.x());
  const double sweep = turn(from - center, to - center);
  c.theta1 = c.theta0 + (convex ? sweep : -sweep);
  return c;
}

bool Fillet::in_cap(const Vec2& corner, const Vec2& p) const {
  return (p - center).norm() > radius && inside_polygon({corner, from, center, to}, p);
}

double Fillet::cap_area(const Vec2& corner) const {
  const double phi = turn(from - center, to - center);
  return radius * (corner - from).norm() - 0.5 * radius * radius * phi;
}

void Domain::round_corner(const Vec2& at, double radius, std::string name) {
  const std::size_t n = vertices_.size();
  std::size_t i = 0;
  while (i < n && (vertices_[i] - at).norm() > 1e-9 * scale_) ++i;
  MF_REQUIRE(i < n, "no corner of the outline lies at (", at.x(), ", ", at.y(), ")");
  MF_REQUIRE(arcs_.empty(), "the outline has arcs of its own: its corners are rounded where it "
                            "is drawn, not by fillets");
  MF_REQUIRE(radius > 0.0, "a fillet's radius must be positive, got ", radius);
  for (const Fillet& f : fillets_)
    MF_REQUIRE(f.vertex != i, "the corner at (", at.x(), ", ", at.y(), ") is rounded already");
  const Vec2& v = vertices_[i];
  const Vec2 in = (v - vertices_[(i + n - 1) % n]).normalized();
  const Vec2 out = (vertices_[(i + 1) % n] - v).normalized();
  const double phi = turn(in, out);
  MF_REQUIRE(phi > 1e-9, "the corner at (", at.x(), ", ", at.y(),
             ") is straight: its edges run on in one line, nothing to round");
  Fillet f;
  f.vertex = i;
  f.radius = radius;
  f.name = name.empty() ? "fillet" + std::to_string(fillets_.size()) : std::move(name);
  f.convex = cross(in, out) > 0.0;
  const double t = radius * std::tan(0.5 * phi);
  f.from = v - t * in;
  f.to = v + t * out;
  const Vec2 left(-in.y(), in.x());
  f.center = f.from + (f.convex ? radius : -radius) * left;
  // The tangent points of the fillets at both ends of an edge must not pass each other.
  const auto used = [&](std::size_t corner) {
    for (const Fillet& g : fillets_)
      if (g.vertex == corner) return (g.from - vertices_[corner]).norm();
    return 0.0;
  };
  const auto fits = [&](std::size_t a, std::size_t b, double ta, double tb) {
    const double length = (vertices_[b] - vertices_[a]).norm();
    MF_REQUIRE(ta + tb <= length * (1.0 + 1e-12), "a fillet of radius ", radius, " at (", at.x(),
               ", ", at.y(), ") needs ", ta + tb, " of edge '", edge_names_[a], "', which is ",
               length, " long");
  };
  fits((i + n - 1) % n, i, used((i + n - 1) % n), t);
  fits(i, (i + 1) % n, t, used((i + 1) % n));
  fillets_.push_back(std::move(f));
  make_outline();
}

void Domain::make_outline() {
  const std::size_t n = vertices_.size();
  std::vector<const Fillet*> at(n, nullptr);
  for (const Fillet& f : fillets_) at[f.vertex] = &f;
  outline_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    Curve c;
    c.kind = Curve::Kind::Segment;
    c.name = edge_names_[i];
    c.a = at[i] ? at[i]->to : vertices_[i];
    c.b = at[j] ? at[j]->from : vertices_[j];
    const bool left = (c.b - c.a).norm() > 1e-12 * (vertices_[j] - vertices_[i]).norm();
    if ((!at[i] && !at[j]) || left) outline_.push_back(c); // else fillets take the whole edge
    if (at[j]) outline_.push_back(at[j]->arc());
  }
}

void Domain::outline_crossings(double x, std::vector<double>& ys) const {
  for (const Curve& c : outline_) vertical_crossings(c, x, ys);
}

} // namespace mf::geometry
