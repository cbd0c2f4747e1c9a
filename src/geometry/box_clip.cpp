#include "meshfree/geometry/box_clip.hpp"
#include <algorithm>
#include <cmath>

namespace mf::geometry {

std::optional<std::pair<double, double>> clip_segment(const Vec2& a, const Vec2& b,
                                                      const BoundingBox& box, double tol) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(d[axis]) <= tol) { // along the slab: all in or all out
      if (a[axis] < box.lo[axis] - tol || a[axis] > box.hi[axis] + tol) return std::nullopt;
      continue;
    }
    double enter = (box.lo[axis] - a[axis]) / d[axis], leave = (box.hi[axis] - a[axis]) / d[axis];
    if (enter > leave) std::swap(enter, leave);
    t0 = std::max(t0, enter), t1 = std::min(t1, leave);
  }
  if (t1 - t0 <= 1e-12) return std::nullopt;
  return std::make_pair(t0, t1);
}

namespace {

/// The polygon cut to the half-plane s x[axis] <= s bound (s = +1 or -1).
std::vector<Vec2> clip_half_plane(const std::vector<Vec2>& in, int axis, double bound, double s) {
  std::vector<Vec2> out;
  const std::size_t n = in.size();
  const auto inside = [&](const Vec2& p) { return s * p[axis] <= s * bound; };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = in[i];
    const Vec2& q = in[(i + 1) % n];
    if (inside(p)) out.push_back(p);
    if (inside(p) != inside(q)) {
      const double t = (bound - p[axis]) / (q[axis] - p[axis]);
      Vec2 x = p + t * (q - p);
      x[axis] = bound; // on the line exactly
      out.push_back(x);
    }
  }
  return out;
}

} // namespace

std::vector<Vec2> clip_polygon(const std::vector<Vec2>& vertices, const BoundingBox& box) {
  std::vector<Vec2> v = vertices;
  for (int axis = 0; axis < 2 && v.size() >= 3; ++axis) {
    v = clip_half_plane(v, axis, box.hi[axis], 1.0);
    if (v.size() >= 3) v = clip_half_plane(v, axis, box.lo[axis], -1.0);
  }
  std::vector<Vec2> out;
  for (const Vec2& p : v)
    if (out.empty() || p != out.back()) out.push_back(p);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

} // namespace mf::geometry
