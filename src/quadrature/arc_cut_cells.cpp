#include "meshfree/quadrature/arc_cut_cells.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::quadrature {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Where the ray from c in direction e meets the lines of the box's edges: it enters at
/// `enter` through the line x[k_enter] = value_enter and leaves at `leave` through x[k_leave] =
/// value_leave (slab method); enter > leave when it misses the box.
struct RayHit {
  double enter = -std::numeric_limits<double>::infinity();
  double leave = std::numeric_limits<double>::infinity();
  int k_enter = -1, k_leave = -1;
  double value_enter = 0.0, value_leave = 0.0;
};

RayHit ray_through_box(const BoundingBox& box, const Vec2& c, const Vec2& e) {
  RayHit h;
  for (int k = 0; k < 2; ++k) {
    if (std::abs(e[k]) < 1e-300) {
      if (c[k] < box.lo[k] || c[k] > box.hi[k]) return {1.0, 0.0};
      continue;
    }
    double t0 = (box.lo[k] - c[k]) / e[k], t1 = (box.hi[k] - c[k]) / e[k];
    double v0 = box.lo[k], v1 = box.hi[k];
    if (t0 > t1) std::swap(t0, t1), std::swap(v0, v1);
    if (t0 > h.enter) h.enter = t0, h.k_enter = k, h.value_enter = v0;
    if (t1 < h.leave) h.leave = t1, h.k_leave = k, h.value_leave = v1;
  }
  return h;
}

/// The point where the ray from c at angle a crosses the line x[k] = value.
Vec2 on_line(const Vec2& c, double a, int k, double value) {
  const Vec2 e(std::cos(a), std::sin(a));
  return c + ((value - c[k]) / e[k]) * e;
}

/// Points of one angular piece [alpha, beta] (absolute angles). Its outer edge, and its inner
/// edge when the arc is not inside, are those the middle ray crosses; the end points are taken
/// on those edges' lines, so that a ray grazing an edge at an end does not matter.
void add_piece(const BoundingBox& box, const Vec2& c, double radius, double alpha, double beta,
               const GaussRule& g, std::vector<Vec2>& x, std::vector<double>& weight) {
  const double mid = 0.5 * (alpha + beta);
  const RayHit m = ray_through_box(box, c, Vec2(std::cos(mid), std::sin(mid)));
  if (m.k_leave < 0 || m.leave <= std::max(radius, m.enter)) return; // in the disc or off the box
  const bool arc_inside = m.enter <= radius; // else the ray enters through an edge
  const Vec2 qa = on_line(c, alpha, m.k_leave, m.value_leave);
  const Vec2 qb = on_line(c, beta, m.k_leave, m.value_leave), dq = qb - qa;
  Vec2 pa = c, dp_line = Vec2::Zero();
  if (!arc_inside) {
    pa = on_line(c, alpha, m.k_enter, m.value_enter);
    dp_line = on_line(c, beta, m.k_enter, m.value_enter) - pa;
  }
  const int n = static_cast<int>(g.points.size());
  for (int i = 0; i < n; ++i) {
    const double s = 0.5 * (g.points[i] + 1.0);
    const Vec2 q = qa + s * dq;
    Vec2 p, dp;
    if (arc_inside) {
      const double l = (q - c).norm();
      const Vec2 u = (q - c) / l;
      p = c + radius * u;
      dp = radius * (dq - u * u.dot(dq)) / l;
    } else {
      p = pa + s * dp_line;
      dp = dp_line;
    }
    const Vec2 xt = q - p;
    for (int j = 0; j < n; ++j) {
      const double t = 0.5 * (g.points[j] + 1.0);
      const Vec2 xs = dp + t * (dq - dp);
      const double jac = std::abs(xs.x() * xt.y() - xs.y() * xt.x());
      x.push_back(p + t * xt);
      weight.push_back(0.25 * g.weights[i] * g.weights[j] * jac);
    }
  }
}

} // namespace

void cell_minus_disc(const BoundingBox& box, const Vec2& center, double radius,
                     const GaussRule& rule, std::vector<Vec2>& x, std::vector<double>& weight) {
  const double tol = 1e-12 * box.size().maxCoeff();
  const Vec2 corner[4] = {box.lo, Vec2(box.hi.x(), box.lo.y()), box.hi,
                          Vec2(box.lo.x(), box.hi.y())};
  const bool centre_inside = box.lo.x() + tol < center.x() && center.x() < box.hi.x() - tol &&
                             box.lo.y() + tol < center.y() && center.y() < box.hi.y() - tol;
  // Angles relative to a reference direction, so that a box seen from outside (which subtends
  // at most half a turn) has no wrap-around: the direction of the box's centre.
  const Vec2 to_mid = 0.5 * (box.lo + box.hi) - center;
  const double reference = centre_inside ? 0.0 : std::atan2(to_mid.y(), to_mid.x());
  const auto relative = [&](const Vec2& p) {
    double a = std::atan2(p.y() - center.y(), p.x() - center.x()) - reference;
    while (a <= -kPi) a += 2.0 * kPi;
    while (a > kPi) a -= 2.0 * kPi;
    return a;
  };
  std::vector<double> cuts;
  double lo = centre_inside ? -kPi : kPi, hi = centre_inside ? kPi : -kPi;
  for (const Vec2& p : corner) {
    if ((p - center).norm() <= tol) continue; // the centre on a corner: no direction
    const double a = relative(p);
    cuts.push_back(a);
    if (!centre_inside) lo = std::min(lo, a), hi = std::max(hi, a);
  }
  for (int k = 0; k < 4; ++k) { // where the circle crosses the edges
    const Vec2 p = corner[k], d = corner[(k + 1) % 4] - p, f = p - center;
    const double a = d.squaredNorm(), b = 2.0 * d.dot(f), cc = f.squaredNorm() - radius * radius;
    const double disc = b * b - 4.0 * a * cc;
    if (disc < 0.0) continue;
    for (double sign : {-1.0, 1.0}) {
      const double t = (-b + sign * std::sqrt(disc)) / (2.0 * a);
      if (t >= 0.0 && t <= 1.0) cuts.push_back(relative(p + t * d));
    }
  }
  cuts.push_back(lo);
  cuts.push_back(hi);
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double a = std::max(cuts[k], lo), b = std::min(cuts[k + 1], hi);
    if (b - a < 1e-12) continue;
    const int parts = static_cast<int>(std::ceil((b - a) / (0.25 * kPi) - 1e-9));
    for (int part = 0; part < parts; ++part)
      add_piece(box, center, radius, reference + a + (b - a) * part / parts,
                reference + a + (b - a) * (part + 1) / parts, rule, x, weight);
  }
}

bool segment_crosses_interior(const BoundingBox& box, const Vec2& a, const Vec2& b, double tol) {
  const BoundingBox inner{box.lo + Vec2::Constant(tol), box.hi - Vec2::Constant(tol)};
  const RayHit h = ray_through_box(inner, a, b - a); // a + t (b - a) inside for t in the hit
  return std::min(h.leave, 1.0) > std::max(h.enter, 0.0);
}

} // namespace mf::quadrature
