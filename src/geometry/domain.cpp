#include "meshfree/geometry/domain.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::geometry {

Vec2 Curve::point(double t) const {
  if (kind == Kind::Segment) return a + t * (b - a);
  const double th = theta0 + t * (theta1 - theta0);
  return center + radius * Vec2(std::cos(th), std::sin(th));
}

double Curve::speed() const {
  return kind == Kind::Segment ? (b - a).norm() : radius * std::abs(theta1 - theta0);
}

Vec2 Curve::outward_normal(double t) const {
  if (kind == Kind::Segment) {
    const Vec2 d = (b - a).normalized();
    return Vec2(d.y(), -d.x()); // right of a counter-clockwise outline
  }
  // Clockwise (a hole's, a re-entrant corner's): the body outside the circle; counter-clockwise
  // (a convex corner's): inside.
  return (theta1 < theta0 ? center - point(t) : point(t) - center) / radius;
}

Curve Curve::piece(double t0, double t1) const {
  Curve c = *this;
  if (kind == Kind::Segment) {
    c.a = point(t0);
    c.b = point(t1);
  } else {
    c.theta0 = theta0 + t0 * (theta1 - theta0);
    c.theta1 = theta0 + t1 * (theta1 - theta0);
  }
  return c;
}

namespace {

/// Whether the direction from an arc's centre to p lies within its sweep: the arc sweeps
/// theta1 - theta0 (either sign) from theta0, and p's angle, measured from theta0 in the sweep's
/// sense and wrapped into [0, 2 pi), lies on the arc when it is within the sweep.
bool within_sweep(const Curve& c, const Vec2& p) {
  const double two_pi = 2.0 * std::acos(-1.0);
  const double sweep = c.theta1 - c.theta0;
  const Vec2 r = p - c.center;
  const double phi = std::atan2(r.y(), r.x());
  const double from = std::fmod(
      std::fmod((sweep >= 0.0 ? phi - c.theta0 : c.theta0 - phi), two_pi) + two_pi, two_pi);
  return from <= std::abs(sweep);
}

/// The parameter of the point of a segment nearest to p.
double segment_parameter(const Curve& c, const Vec2& p) {
  const Vec2 d = c.b - c.a;
  return std::clamp((p - c.a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
}

} // namespace

void vertical_crossings(const Curve& c, double x, std::vector<double>& ys) {
  if (c.kind == Curve::Kind::Segment) {
    if ((c.a.x() - x) * (c.b.x() - x) < 0.0)
      ys.push_back(c.a.y() + (x - c.a.x()) / (c.b.x() - c.a.x()) * (c.b.y() - c.a.y()));
    else if (c.a.x() == x)
      ys.push_back(c.a.y());
    return;
  }
  const double dx = x - c.center.x(), r2 = c.radius * c.radius - dx * dx;
  if (r2 < 0.0) return;
  for (const double y : {c.center.y() - std::sqrt(r2), c.center.y() + std::sqrt(r2)})
    if (within_sweep(c, Vec2(x, y))) ys.push_back(y);
}

double Curve::distance_to(const Vec2& p) const {
  if (kind == Kind::Segment) return (p - point(segment_parameter(*this, p))).norm();
  if (within_sweep(*this, p)) return std::abs((p - center).norm() - radius);
  return std::min((p - point(0.0)).norm(), (p - point(1.0)).norm());
}

Vec2 Curve::closest_point(const Vec2& p) const {
  if (kind == Kind::Segment) return point(segment_parameter(*this, p));
  const Vec2 r = p - center;
  if (within_sweep(*this, p) && r.norm() > 0.0) return center + radius * r / r.norm();
  return (p - point(0.0)).norm() <= (p - point(1.0)).norm() ? point(0.0) : point(1.0);
}

bool Curve::crossed_by(const Vec2& a, const Vec2& b, double tol) const {
  const Vec2 d = b - a;
  const double length = d.norm();
  if (!(length > 2.0 * tol)) return false;
  const auto side = [](const Vec2& p, const Vec2& q, const Vec2& x) { // signed distance to p-q
    const Vec2 e = q - p;
    return (e.x() * (x.y() - p.y()) - e.y() * (x.x() - p.x())) / e.norm();
  };
  if (kind == Kind::Segment) {
    // By the signs of distances, not a quotient of them: a and b each off the piece's line by
    // more than tol and on either side of it (so a point on the piece hides nothing), and the
    // piece's ends not both strictly on one side of a-b.
    if (!((this->b - this->a).norm() > 0.0)) return false;
    const double da = side(this->a, this->b, a), db = side(this->a, this->b, b);
    if (!(std::abs(da) > tol && std::abs(db) > tol && (da > 0.0) != (db > 0.0))) return false;
    const double ea = side(a, b, this->a), eb = side(a, b, this->b);
    return !(ea > 0.0 && eb > 0.0) && !(ea < 0.0 && eb < 0.0);
  }
  // |a + t d - c| = r: d.d t^2 + 2 d.(a - c) t + |a - c|^2 - r^2 = 0.
  const double lo = tol / length, hi = 1.0 - tol / length; // the open part of a..b
  const Vec2 f = a - center;
  const double A = d.squaredNorm(), B = 2.0 * d.dot(f), C = f.squaredNorm() - radius * radius;
  const double disc = B * B - 4.0 * A * C;
  if (disc < 0.0) return false;
  for (const double t : {(-B - std::sqrt(disc)) / (2.0 * A), (-B + std::sqrt(disc)) / (2.0 * A)})
    if (t > lo && t < hi && within_sweep(*this, a + t * d)) return true;
  return false;
}

Domain Domain::rectangle(const Vec2& origin, const Vec2& size) {
  MF_REQUIRE(size.x() > 0.0 && size.y() > 0.0, "rectangle size must be positive");
  return polygon(
      {origin, origin + Vec2(size.x(), 0.0), origin + size, origin + Vec2(0.0, size.y())},
      {"bottom", "right", "top", "left"});
}

Domain Domain::polygon(std::vector<Vec2> vertices, std::vector<std::string> edge_names) {
  const std::size_t n = vertices.size();
  MF_REQUIRE(n >= 3, "a polygon needs at least 3 vertices, got ", n);
  if (edge_names.empty())
    for (std::size_t i = 0; i < n; ++i) edge_names.push_back("edge" + std::to_string(i));
  MF_REQUIRE(edge_names.size() == n, "a polygon with ", n, " vertices needs ", n,
             " edge names, got ", edge_names.size());
  const double area = signed_area(vertices);
  MF_REQUIRE(std::abs(area) > 0.0, "polygon has zero area");
  if (area < 0.0) { // make it counter-clockwise; edge i (v_i -> v_i+1) keeps its name
    std::vector<Vec2> v(vertices.rbegin(), vertices.rend());
    std::vector<std::string> names(n);
    for (std::size_t i = 0; i < n; ++i) names[i] = edge_names[(2 * n - 2 - i) % n];
    vertices.swap(v);
    edge_names.swap(names);
  }
  Domain d;
  d.vertices_ = std::move(vertices);
  d.edge_names_ = std::move(edge_names);
  d.make_outline();
  const BoundingBox bb = d.bounds();
  d.scale_ = bb.size().maxCoeff();
  return d;
}

void Domain::add_hole(const Circle& hole) {
  MF_REQUIRE(hole.radius > 0.0, "hole radius must be positive, got ", hole.radius);
  holes_.push_back(hole);
  if (holes_.back().name.empty())
    holes_.back().name = "hole" + std::to_string(holes_.size() + outline_holes_.size() - 1);
}

void Domain::add_hole(const OutlineHole& hole) {
  outline_holes_.push_back(hole);
  if (outline_holes_.back().name.empty())
    outline_holes_.back().name = "hole" + std::to_string(holes_.size() + outline_holes_.size() - 1);
}

void Domain::add_holes_of(const Domain& other) {
  for (const Circle& h : other.holes_) add_hole(h);
  for (const OutlineHole& h : other.outline_holes_) add_hole(h);
}

double Domain::distance_to_boundary(const Vec2& p) const {
  double d = distance_to_outline(p);
  for (const Circle& c : holes_) d = std::min(d, std::abs((p - c.center).norm() - c.radius));
  for (const OutlineHole& h : outline_holes_) d = std::min(d, h.distance_to(p));
  return d;
}

void Domain::hole_crossings(double x, std::vector<double>& ys) const {
  for (const Circle& h : holes_) {
    const double dx = x - h.center.x();
    if (std::abs(dx) >= h.radius) continue;
    const double half = std::sqrt(h.radius * h.radius - dx * dx);
    ys.push_back(h.center.y() - half);
    ys.push_back(h.center.y() + half);
  }
  for (const OutlineHole& h : outline_holes_)
    for (const Curve& c : h.loop()) vertical_crossings(c, x, ys);
}

std::vector<std::string> Domain::names_selected(const std::string& name) const {
  for (const Curve& c : boundary())
    if (c.name == name) return {name};
  static const char* const sides[4] = {"x_min", "x_max", "y_min", "y_max"};
  const auto side = std::find(sides, sides + 4, name);
  if (side == sides + 4) return {};
  const int axis = static_cast<int>(side - sides) / 2;
  const BoundingBox b = bounds();
  const double at = (side - sides) % 2 ? b.hi(axis) : b.lo(axis);
  const double tol = 1e-9 * b.size().maxCoeff();
  std::vector<std::string> out;
  for (const Curve& c : outline_) {
    const bool on = c.kind == Curve::Kind::Segment && std::abs(c.a(axis) - at) <= tol &&
                    std::abs(c.b(axis) - at) <= tol;
    if (on && std::find(out.begin(), out.end(), c.name) == out.end()) out.push_back(c.name);
  }
  return out;
}

BoundingBox Domain::bounds() const {
  if (has_arcs()) return loop_bounds(outline_);
  BoundingBox bb{vertices_[0], vertices_[0]};
  for (const auto& v : vertices_) bb.lo = bb.lo.cwiseMin(v), bb.hi = bb.hi.cwiseMax(v);
  return bb;
}

double Domain::area_estimate() const {
  double area = signed_area(vertices_); // holes ignored: used only for sizing estimates
  for (const Fillet& f : fillets_)
    area += (f.convex ? -1.0 : 1.0) * f.cap_area(vertices_[f.vertex]);
  return arcs_.empty() ? area : loop_area(outline_);
}

double signed_area(const std::vector<Vec2>& vertices) {
  double area2 = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec2& p = vertices[i];
    const Vec2& q = vertices[(i + 1) % vertices.size()];
    area2 += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * area2;
}

bool inside_polygon(const std::vector<Vec2>& vertices, const Vec2& p) {
  bool inside = false; // even-odd crossing rule
  const std::size_t n = vertices.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& vi = vertices[i];
    const Vec2& vj = vertices[j];
    if ((vi.y() > p.y()) != (vj.y() > p.y()) &&
        p.x() < (vj.x() - vi.x()) * (p.y() - vi.y()) / (vj.y() - vi.y()) + vi.x())
      inside = !inside;
  }
  return inside;
}

bool Domain::inside_outline(const Vec2& p) const {
  bool inside = geometry::inside_polygon(vertices_, p);
  for (const Fillet& f : fillets_) // the caps lie inside (convex) or outside the sharp polygon
    if (f.in_cap(vertices_[f.vertex], p)) inside = !f.convex;
  return arcs_.empty() ? inside : inside_loop(outline_, p);
}

namespace {

/// The distance from p to the closed polygon through `vertices`.
double distance_to_polygon(const std::vector<Vec2>& vertices, const Vec2& p) {
  double d = std::numeric_limits<double>::max();
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = vertices[i];
    const Vec2 ab = vertices[(i + 1) % n] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + t * ab - p).norm());
  }
  return d;
}

/// The distance from p to the segment a-b.
double distance_to_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

/// True where the segments p-q and r-s share a point.
bool segments_meet(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
  const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, r - p), d2 = cross(q - p, s - p);
  const double d3 = cross(s - r, p - r), d4 = cross(s - r, q - r);
  if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0)
    return true;
  const auto on = [&](const Vec2& a, const Vec2& b, const Vec2& x, double c) {
    return c == 0.0 && x.x() >= std::min(a.x(), b.x()) && x.x() <= std::max(a.x(), b.x()) &&
           x.y() >= std::min(a.y(), b.y()) && x.y() <= std::max(a.y(), b.y());
  };
  return on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) || on(r, s, q, d4);
}

} // namespace

double Domain::distance_to_outline(const Vec2& p) const {
  if (!has_arcs()) return distance_to_polygon(vertices_, p);
  double d = std::numeric_limits<double>::max();
  for (const Curve& c : outline_) d = std::min(d, c.distance_to(p));
  return d;
}

OutlineHole OutlineHole::polygon(std::vector<Vec2> vertices, std::string name) {
  const std::size_t n = vertices.size();
  MF_REQUIRE(n >= 3, "a polygon hole needs at least 3 vertices, got ", n);
  const double area = signed_area(vertices);
  MF_REQUIRE(std::abs(area) > 0.0, "the polygon hole has zero area");
  if (area < 0.0) std::reverse(vertices.begin(), vertices.end());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue; // adjacent through the closing edge
      MF_REQUIRE(!segments_meet(vertices[i], vertices[i + 1], vertices[j], vertices[(j + 1) % n]),
                 "the polygon hole's edges ", i, " and ", j,
                 " cross: its outline must not cross "
                 "itself");
    }
  OutlineHole h;
  h.kind = Kind::Polygon;
  h.vertices = std::move(vertices);
  h.name = std::move(name);
  return h;
}

OutlineHole OutlineHole::slot(const Vec2& a, const Vec2& b, double half_width, std::string name) {
  MF_REQUIRE(half_width > 0.0, "a slot's width must be positive, got ", 2.0 * half_width);
  OutlineHole h;
  h.kind = Kind::Slot;
  h.a = a;
  h.b = b;
  h.half_width = half_width;
  h.name = std::move(name);
  return h;
}

bool OutlineHole::contains(const Vec2& p, double tol) const {
  if (kind == Kind::Slot) return distance_to_segment(a, b, p) < half_width - tol;
  if (kind == Kind::Loop) return inside_loop(curves, p) && distance_to(p) > tol;
  return inside_polygon(vertices, p) && distance_to_polygon(vertices, p) > tol;
}

double OutlineHole::distance_to(const Vec2& p) const {
  if (kind == Kind::Slot) return std::abs(distance_to_segment(a, b, p) - half_width);
  if (kind == Kind::Loop) {
    double d = std::numeric_limits<double>::max();
    for (const Curve& c : curves) d = std::min(d, c.distance_to(p));
    return d;
  }
  return distance_to_polygon(vertices, p);
}

std::vector<Curve> OutlineHole::loop() const {
  if (kind == Kind::Loop) return curves;
  std::vector<Curve> out;
  const auto segment = [&](const Vec2& from, const Vec2& to) {
    Curve c;
    c.name = name;
    c.a = from;
    c.b = to;
    out.push_back(c);
  };
  if (kind == Kind::Polygon) { // clockwise: each edge backwards, the hole on its right
    for (std::size_t i = vertices.size(); i-- > 0;)
      segment(vertices[(i + 1) % vertices.size()], vertices[i]);
    return out;
  }
  const double pi = std::acos(-1.0);
  const Vec2 d = b - a;
  const double length = d.norm();
  // The slot's axis, and its side normal n: along +n the side runs from a to b, then the end
  // round b clockwise from +n to -n, the other side back, the end round a.
  const Vec2 u = length > 0.0 ? Vec2(d / length) : Vec2(1.0, 0.0);
  const Vec2 n(-u.y(), u.x());
  const double at_n = std::atan2(n.y(), n.x());
  const auto arc = [&](const Vec2& centre, double from) {
    Curve c;
    c.kind = Curve::Kind::Arc;
    c.name = name;
    c.center = centre;
    c.radius = half_width;
    c.theta0 = from;
    c.theta1 = from - pi;
    out.push_back(c);
  };
  if (length > 0.0) segment(a + half_width * n, b + half_width * n);
  arc(b, at_n);
  if (length > 0.0) segment(b - half_width * n, a - half_width * n);
  arc(a, at_n - pi);
  return out;
}

BoundingBox OutlineHole::bounds() const {
  if (kind == Kind::Slot) {
    const Vec2 r(half_width, half_width);
    return {a.cwiseMin(b) - r, a.cwiseMax(b) + r};
  }
  if (kind == Kind::Loop) return loop_bounds(curves);
  BoundingBox bb{vertices[0], vertices[0]};
  for (const Vec2& v : vertices) bb.lo = bb.lo.cwiseMin(v), bb.hi = bb.hi.cwiseMax(v);
  return bb;
}

double OutlineHole::area() const {
  if (kind == Kind::Slot)
    return 4.0 * half_width * (b - a).norm() / 2.0 + std::acos(-1.0) * half_width * half_width;
  if (kind == Kind::Loop) return -loop_area(curves);
  return signed_area(vertices);
}

bool Domain::within_outline(const Vec2& p, double tol) const {
  return inside_outline(p) || distance_to_outline(p) <= tol * scale_;
}

bool Domain::contains(const Vec2& p, double tol) const {
  const double abs_tol = tol * scale_;
  if (!within_outline(p, tol)) return false;
  for (const auto& h : holes_)
    if ((p - h.center).norm() < h.radius - abs_tol) return false;
  for (const auto& h : outline_holes_)
    if (h.contains(p, abs_tol)) return false;
  return true;
}

std::vector<std::pair<double, double>>
kept_intervals(const Curve& curve, const std::function<bool(const Vec2&)>& keep) {
  constexpr int samples = 512;
  std::vector<std::pair<double, double>> out;
  auto transition = [&](double lo, double hi, bool keep_lo) {
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (keep(curve.point(mid)) == keep_lo ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  bool prev = keep(curve.point(0.0));
  double start = 0.0;
  for (int k = 1; k <= samples; ++k) {
    const double t = static_cast<double>(k) / samples;
    const bool now = keep(curve.point(t));
    if (now != prev) {
      const double tc = transition(static_cast<double>(k - 1) / samples, t, prev);
      if (prev)
        out.emplace_back(start, tc);
      else
        start = tc;
      prev = now;
    }
  }
  if (prev) out.emplace_back(start, 1.0);
  // drop slivers left by tangency
  out.erase(std::remove_if(out.begin(), out.end(),
                           [](const auto& iv) { return iv.second - iv.first < 1e-10; }),
            out.end());
  return out;
}

std::vector<Curve> Domain::boundary() const {
  std::vector<Curve> curves;
  const double tol = 1e-14;
  auto outside_holes = [&](const Vec2& p, const void* except) {
    for (const auto& h : holes_)
      if (&h != except && (p - h.center).norm() < h.radius * (1.0 - tol)) return false;
    for (const auto& h : outline_holes_)
      if (&h != except && h.contains(p, tol * scale_)) return false;
    return true;
  };
  for (const Curve& c : outline_) {
    for (const auto& [t0, t1] :
         kept_intervals(c, [&](const Vec2& p) { return outside_holes(p, nullptr); }))
      curves.push_back(c.piece(t0, t1));
  }
  for (const auto& h : holes_) {
    Curve c;
    c.kind = Curve::Kind::Arc;
    c.name = h.name;
    c.center = h.center;
    c.radius = h.radius;
    c.theta0 = 2.0 * M_PI; // clockwise, so the body stays on the left
    c.theta1 = 0.0;
    auto keep = [&](const Vec2& p) {
      return (inside_outline(p) || distance_to_outline(p) <= tol * scale_) && outside_holes(p, &h);
    };
    for (const auto& [t0, t1] : kept_intervals(c, keep)) curves.push_back(c.piece(t0, t1));
  }
  for (const auto& h : outline_holes_)
    for (const Curve& c : h.loop()) {
      auto keep = [&](const Vec2& p) { return within_outline(p, tol) && outside_holes(p, &h); };
      for (const auto& [t0, t1] : kept_intervals(c, keep)) curves.push_back(c.piece(t0, t1));
    }
  // An arc cut at parameter 0/1 appears as two pieces meeting at theta = 0; that is harmless.
  return curves;
}

} // namespace mf::geometry
