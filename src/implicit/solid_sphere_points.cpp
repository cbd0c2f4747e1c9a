#include "meshfree/implicit/solid_sphere_points.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A sphere in polar coordinates about one of the axes: w along the pole axis from the centre,
/// phi the longitude from the next axis (x after z, y after x, z after y), so that planes
/// through the centre normal to an axis are latitudes or meridians at quarter turns.
struct Polar {
  const geometry::Sphere& s;
  int axis = 2;
  Vec3 at(double w, double phi) const {
    const double rho = std::sqrt(std::max(0.0, s.radius * s.radius - w * w));
    return from(w, rho * std::cos(phi), rho * std::sin(phi));
  }
  Vec3 from(double w, double u, double v) const {
    Vec3 x = s.center;
    x(axis) += w;
    x((axis + 1) % 3) += u;
    x((axis + 2) % 3) += v;
    return x;
  }
};

/// One patch [w0, w1] x [phi0, phi1] of the surface; its area element is r dw dphi.
struct Patch {
  double w0, w1, phi0, phi1;
  double w(double u) const { return 0.5 * (w0 + w1) + 0.5 * u * (w1 - w0); }
  double phi(double v) const { return 0.5 * (phi0 + phi1) + 0.5 * v * (phi1 - phi0); }
};

/// The pole axis of a sphere's patches: one whose end planes cut the sphere off its centre (the
/// body's bounding box's faces normal to it), so that those cuts are latitudes; z by default.
int pole_axis(const geometry::Prism& body, const geometry::Sphere& s) {
  const BoundingBox b = body.section.bounds();
  const Vec3 lo(b.lo.x(), b.lo.y(), body.z0), hi(b.hi.x(), b.hi.y(), body.z1());
  const double tol = 1e-9 * body.size();
  const auto cuts_off_centre = [&](int a) {
    for (const double plane : {lo(a), hi(a)}) {
      const double d = std::abs(plane - s.center(a));
      if (d > tol && d < s.radius) return true;
    }
    return false;
  };
  if (cuts_off_centre(2)) return 2;
  for (int a : {0, 1})
    if (cuts_off_centre(a)) return a;
  return 2;
}

void add_point(const Polar& p, const Vec3& x, double w, SolidPoints& out) {
  out.x.push_back(x);
  out.weight.push_back(w);
  out.normal.push_back((p.s.center - x) / p.s.radius);
}

/// A patch the body's other boundaries cut: its w range clipped to the body's bounding box
/// along the pole axis (exact where those planes are the body's faces: they are latitudes), then
/// along each Gauss latitude the arcs in the body (found by bisection, geometry::kept_intervals),
/// each with its own Gauss rule in phi.
void cut_patch_by_latitudes(const geometry::Prism& body, const Polar& p, Patch q,
                            const GaussRule& g, SolidPoints& out) {
  const BoundingBox b = body.section.bounds();
  const Vec3 lo(b.lo.x(), b.lo.y(), body.z0), hi(b.hi.x(), b.hi.y(), body.z1());
  q.w0 = std::max(q.w0, lo(p.axis) - p.s.center(p.axis));
  q.w1 = std::min(q.w1, hi(p.axis) - p.s.center(p.axis));
  if (q.w1 <= q.w0) return;
  const int n = static_cast<int>(g.points.size());
  for (int i = 0; i < n; ++i) {
    const double w = q.w(g.points[i]);
    geometry::Curve latitude;
    latitude.kind = geometry::Curve::Kind::Arc;
    latitude.radius = std::sqrt(std::max(0.0, p.s.radius * p.s.radius - w * w));
    latitude.theta0 = q.phi0;
    latitude.theta1 = q.phi1;
    const auto in_body = [&](const Vec2& uv) { // a tight tolerance: the arc's ends are found to it
      return body.contains(p.from(w, uv.x(), uv.y()), 1e-14);
    };
    for (const auto& [t0, t1] : geometry::kept_intervals(latitude, in_body)) {
      if (t1 - t0 < 1e-7) continue; // a sliver the tolerance of the body's faces let in
      const Patch arc{q.w0, q.w1, q.phi0 + t0 * (q.phi1 - q.phi0), q.phi0 + t1 * (q.phi1 - q.phi0)};
      for (int j = 0; j < n; ++j)
        add_point(p, p.at(w, arc.phi(g.points[j])),
                  g.weights[i] * g.weights[j] * 0.25 * p.s.radius * (arc.w1 - arc.w0) *
                      (arc.phi1 - arc.phi0),
                  out);
    }
  }
}

/// A patch's Gauss points in the body, the patch split into four `levels` times where the
/// body's other boundaries cut it, then integrated along latitudes.
void surface_patch(const geometry::Prism& body, const Polar& p, const Patch& q, const GaussRule& g,
                   int levels, SolidPoints& out) {
  const int n = static_cast<int>(g.points.size());
  int inside = 0, total = 0;
  for (const double u : {-1.0, 1.0})
    for (const double v : {-1.0, 1.0})
      inside += body.contains(p.at(q.w(u), q.phi(v)), 1e-9), ++total;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      inside += body.contains(p.at(q.w(g.points[i]), q.phi(g.points[j])), 1e-9), ++total;
  if (inside == 0) return;
  if (inside < total && levels > 0) {
    const double wm = q.w(0.0), pm = q.phi(0.0);
    for (const auto& [wa, wb] : {std::pair{q.w0, wm}, std::pair{wm, q.w1}})
      for (const auto& [pa, pb] : {std::pair{q.phi0, pm}, std::pair{pm, q.phi1}})
        surface_patch(body, p, {wa, wb, pa, pb}, g, levels - 1, out);
    return;
  }
  if (inside < total) return cut_patch_by_latitudes(body, p, q, g, out);
  const double jac = 0.25 * p.s.radius * (q.w1 - q.w0) * (q.phi1 - q.phi0); // dA = r dw dphi
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 x = p.at(q.w(g.points[i]), q.phi(g.points[j]));
      if (body.contains(x, 1e-9)) add_point(p, x, g.weights[i] * g.weights[j] * jac, out);
    }
}

/// The parts of [a, b] outside every sphere along the line through p in direction `axis`.
std::vector<std::pair<double, double>> outside_balls(const geometry::Prism& body, const Vec3& p,
                                                     int axis, double a, double b) {
  std::vector<std::pair<double, double>> parts{{a, b}};
  for (const geometry::Sphere& s : body.spheres) {
    Vec3 d = p - s.center;
    d(axis) = 0.0;
    const double h2 = s.radius * s.radius - d.squaredNorm();
    if (h2 <= 0.0) continue;
    const double lo = s.center(axis) - std::sqrt(h2), hi = s.center(axis) + std::sqrt(h2);
    std::vector<std::pair<double, double>> kept;
    for (const auto& [u, v] : parts) {
      if (std::min(v, lo) > u) kept.emplace_back(u, std::min(v, lo));
      if (v > std::max(u, hi)) kept.emplace_back(std::max(u, hi), v);
    }
    parts = kept;
  }
  return parts;
}

/// A finest cut cell: Gauss lines along the axis nearest the normal of the sphere that cuts it,
/// each on its parts outside the balls; points outside the rest of the body dropped.
void cut_cell_by_lines(const geometry::Prism& body, const Vec3& lo, const Vec3& hi,
                       const GaussRule& g, SolidPoints& out) {
  const Vec3 mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const geometry::Sphere* nearest = &body.spheres.front();
  for (const geometry::Sphere& s : body.spheres)
    if (std::abs(s.distance(mid)) < std::abs(nearest->distance(mid))) nearest = &s;
  int axis = 0;
  (mid - nearest->center).cwiseAbs().maxCoeff(&axis);
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  const int n = static_cast<int>(g.points.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Vec3 p = mid;
      p(b) += g.points[i] * half(b);
      p(c) += g.points[j] * half(c);
      const double w = g.weights[i] * g.weights[j] * half(b) * half(c);
      for (const auto& [t0, t1] : outside_balls(body, p, axis, lo(axis), hi(axis)))
        for (int k = 0; k < n; ++k) {
          p(axis) = 0.5 * (t0 + t1) + 0.5 * g.points[k] * (t1 - t0);
          if (!body.contains(p, 1e-9)) continue;
          out.x.push_back(p);
          out.weight.push_back(w * g.weights[k] * 0.5 * (t1 - t0));
        }
    }
}

/// The nearest and farthest distance from the sphere's centre to the box.
std::pair<double, double> reach(const geometry::Sphere& s, const Vec3& lo, const Vec3& hi) {
  const Vec3 nearest = s.center.cwiseMax(lo).cwiseMin(hi);
  const Vec3 far = (s.center - lo).cwiseAbs().cwiseMax((s.center - hi).cwiseAbs());
  return {(nearest - s.center).norm(), far.norm()};
}

} // namespace

SolidPoints sphere_face_points(const geometry::Prism& body, const geometry::Sphere& s, double part,
                               int order, int cut_levels) {
  const GaussRule& g = gauss_legendre(order);
  const Polar p{s, pole_axis(body, s)};
  SolidPoints out;
  const int rings = geometry::latitude_rings(s.radius, part);
  for (int i = 0; i < rings; ++i) {
    // bands between rings even in polar angle, integrated in w (where dA = r dw dphi)
    const double w1 = s.radius * std::cos(kPi * i / rings);
    const double w0 = s.radius * std::cos(kPi * (i + 1) / rings);
    const int count =
        geometry::ring_points(2.0 * kPi * s.radius * std::sin(kPi * (i + 0.5) / rings), part);
    for (int j = 0; j < count; ++j)
      surface_patch(body, p, {w0, w1, 2.0 * kPi * j / count, 2.0 * kPi * (j + 1) / count}, g,
                    cut_levels, out);
  }
  return out;
}

bool sphere_touches(const geometry::Prism& body, const Vec3& lo, const Vec3& hi) {
  return std::any_of(body.spheres.begin(), body.spheres.end(),
                     [&](const geometry::Sphere& s) { return reach(s, lo, hi).first < s.radius; });
}

void sphere_cell_points(const geometry::Prism& body, const Vec3& lo, const Vec3& hi, int order,
                        int cut_levels, const quadrature::CellSizing& sizing, SolidPoints& out) {
  const Vec3 half = 0.5 * (hi - lo), mid = lo + half;
  const BoundingBox plane{lo.head<2>(), hi.head<2>()};
  const bool coarse =
      sizing.spacing > 0.0 && (hi - lo).maxCoeff() > sizing.size_at(plane) * (1.0 + 1e-9);
  bool cut = false;
  for (const geometry::Sphere& s : body.spheres) {
    const auto [near, far] = reach(s, lo, hi);
    if (far <= s.radius) return; // the whole cell lies in a ball
    cut = cut || near < s.radius;
  }
  if (coarse || (cut && cut_levels > 0)) {
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner =
          lo + Vec3((k & 1) * half.x(), ((k >> 1) & 1) * half.y(), ((k >> 2) & 1) * half.z());
      sphere_cell_points(body, corner, corner + half, order, cut_levels - (coarse ? 0 : 1), sizing,
                         out);
    }
    return;
  }
  const GaussRule& g = gauss_legendre(order);
  if (cut) return cut_cell_by_lines(body, lo, hi, g, out);
  const int n = static_cast<int>(g.points.size());
  const double jac = half.prod();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 p = mid + Vec3(g.points[i], g.points[j], g.points[k]).cwiseProduct(half);
        if (!body.contains(p, 1e-9)) continue;
        out.x.push_back(p);
        out.weight.push_back(g.weights[i] * g.weights[j] * g.weights[k] * jac);
      }
}

} // namespace mf::implicit
