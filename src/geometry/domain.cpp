#include "meshfree/geometry/domain.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>

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
  return (center - point(t)) / radius; // body outside the hole
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
  const BoundingBox bb = d.bounds();
  d.scale_ = bb.size().maxCoeff();
  return d;
}

void Domain::add_hole(const Circle& hole) {
  MF_REQUIRE(hole.radius > 0.0, "hole radius must be positive, got ", hole.radius);
  holes_.push_back(hole);
  if (holes_.back().name.empty()) holes_.back().name = "hole" + std::to_string(holes_.size() - 1);
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
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const bool on = std::abs(vertices_[i](axis) - at) <= tol &&
                    std::abs(vertices_[(i + 1) % n](axis) - at) <= tol;
    if (on && std::find(out.begin(), out.end(), edge_names_[i]) == out.end())
      out.push_back(edge_names_[i]);
  }
  return out;
}

BoundingBox Domain::bounds() const {
  BoundingBox bb{vertices_[0], vertices_[0]};
  for (const auto& v : vertices_) {
    bb.lo = bb.lo.cwiseMin(v);
    bb.hi = bb.hi.cwiseMax(v);
  }
  return bb;
}

double Domain::area_estimate() const {
  return signed_area(vertices_); // holes ignored: used only for sizing estimates
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

bool Domain::inside_polygon(const Vec2& p) const {
  bool inside = false; // even-odd crossing rule
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& vi = vertices_[i];
    const Vec2& vj = vertices_[j];
    if ((vi.y() > p.y()) != (vj.y() > p.y()) &&
        p.x() < (vj.x() - vi.x()) * (p.y() - vi.y()) / (vj.y() - vi.y()) + vi.x())
      inside = !inside;
  }
  return inside;
}

double Domain::distance_to_outline(const Vec2& p) const {
  double d = std::numeric_limits<double>::max();
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = vertices_[i];
    const Vec2 ab = vertices_[(i + 1) % n] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + t * ab - p).norm());
  }
  return d;
}

bool Domain::within_outline(const Vec2& p, double tol) const {
  return inside_polygon(p) || distance_to_outline(p) <= tol * scale_;
}

bool Domain::contains(const Vec2& p, double tol) const {
  const double abs_tol = tol * scale_;
  if (!within_outline(p, tol)) return false;
  for (const auto& h : holes_)
    if ((p - h.center).norm() < h.radius - abs_tol) return false;
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
  auto outside_holes = [&](const Vec2& p, const Circle* except) {
    for (const auto& h : holes_)
      if (&h != except && (p - h.center).norm() < h.radius * (1.0 - tol)) return false;
    return true;
  };
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0; i < n; ++i) {
    Curve c;
    c.kind = Curve::Kind::Segment;
    c.name = edge_names_[i];
    c.a = vertices_[i];
    c.b = vertices_[(i + 1) % n];
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
      return (inside_polygon(p) || distance_to_outline(p) <= tol * scale_) && outside_holes(p, &h);
    };
    for (const auto& [t0, t1] : kept_intervals(c, keep)) curves.push_back(c.piece(t0, t1));
  }
  // An arc cut at parameter 0/1 appears as two pieces meeting at theta = 0; that is harmless.
  return curves;
}

} // namespace mf::geometry
