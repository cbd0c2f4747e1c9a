#include "meshfree/implicit/solid_sphere_points.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 on_sphere(const geometry::Sphere& s, double z, double phi) {
  const double rho = std::sqrt(std::max(0.0, s.radius * s.radius - z * z));
  return s.center + Vec3(rho * std::cos(phi), rho * std::sin(phi), z);
}

/// A patch the body's other boundaries cut: its z range clipped to the prism's ends (exact:
/// they are latitudes), then along each Gauss latitude the arcs in the body (found by bisection,
/// geometry::kept_intervals), each with its own Gauss rule in phi.
void cut_patch_by_latitudes(const geometry::Prism& body, const geometry::Sphere& s, double z0,
                            double z1, double phi0, double phi1, const GaussRule& g,
                            SolidPoints& out) {
  z0 = std::max(z0, body.z0 - s.center.z());
  z1 = std::min(z1, body.z1() - s.center.z());
  if (z1 <= z0) return;
  const int n = static_cast<int>(g.points.size());
  for (int i = 0; i < n; ++i) {
    const double z = 0.5 * (z0 + z1) + 0.5 * g.points[i] * (z1 - z0);
    geometry::Curve latitude;
    latitude.kind = geometry::Curve::Kind::Arc;
    latitude.center = s.center.head<2>();
    latitude.radius = std::sqrt(std::max(0.0, s.radius * s.radius - z * z));
    latitude.theta0 = phi0;
    latitude.theta1 = phi1;
    const auto in_body = [&](const Vec2& xy) {
      // a tight tolerance: the arc's ends are found to it
      return body.contains(Vec3(xy.x(), xy.y(), s.center.z() + z), 1e-14);
    };
    for (const auto& [t0, t1] : geometry::kept_intervals(latitude, in_body)) {
      if (t1 - t0 < 1e-7) continue; // a sliver the tolerance of the body's faces let in
      const double a = phi0 + t0 * (phi1 - phi0), b = phi0 + t1 * (phi1 - phi0);
      for (int j = 0; j < n; ++j) {
        const Vec3 x = on_sphere(s, z, 0.5 * (a + b) + 0.5 * g.points[j] * (b - a));
        out.x.push_back(x);
        out.weight.push_back(g.weights[i] * g.weights[j] * 0.25 * s.radius * (z1 - z0) * (b - a));
        out.normal.push_back((s.center - x) / s.radius);
      }
    }
  }
}

/// One patch [z0, z1] x [phi0, phi1] of a sphere's surface: its Gauss points in the body, the
/// patch split into four where the body's other boundaries cut it.
void surface_patch(const geometry::Prism& body, const geometry::Sphere& s, double z0, double z1,
                   double phi0, double phi1, const GaussRule& g, int levels, SolidPoints& out) {
  const int n = static_cast<int>(g.points.size());
  const auto at = [&](double u, double v) {
    return on_sphere(s, 0.5 * (z0 + z1) + 0.5 * u * (z1 - z0),
                     0.5 * (phi0 + phi1) + 0.5 * v * (phi1 - phi0));
  };
  int inside = 0, total = 0;
  for (const double u : {-1.0, 1.0})
    for (const double v : {-1.0, 1.0}) inside += body.contains(at(u, v), 1e-9), ++total;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      inside += body.contains(at(g.points[i], g.points[j]), 1e-9), ++total;
  if (inside == 0) return;
  if (inside < total && levels > 0) {
    const double zm = 0.5 * (z0 + z1), pm = 0.5 * (phi0 + phi1);
    for (const auto& [za, zb] : {std::pair{z0, zm}, std::pair{zm, z1}})
      for (const auto& [pa, pb] : {std::pair{phi0, pm}, std::pair{pm, phi1}})
        surface_patch(body, s, za, zb, pa, pb, g, levels - 1, out);
    return;
  }
  if (inside < total) return cut_patch_by_latitudes(body, s, z0, z1, phi0, phi1, g, out);
  // dA = r dz dphi
  const double jac = 0.25 * s.radius * (z1 - z0) * (phi1 - phi0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 x = at(g.points[i], g.points[j]);
      if (!body.contains(x, 1e-9)) continue;
      out.x.push_back(x);
      out.weight.push_back(g.weights[i] * g.weights[j] * jac);
      out.normal.push_back((s.center - x) / s.radius);
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
  SolidPoints out;
  const int rings = geometry::latitude_rings(s.radius, part);
  for (int i = 0; i < rings; ++i) {
    // bands between rings even in polar angle, integrated in z (where dA = r dz dphi)
    const double z1 = s.radius * std::cos(kPi * i / rings);
    const double z0 = s.radius * std::cos(kPi * (i + 1) / rings);
    const double mid = std::sin(kPi * (i + 0.5) / rings);
    const int count = geometry::ring_points(2.0 * kPi * s.radius * mid, part);
    for (int j = 0; j < count; ++j)
      surface_patch(body, s, z0, z1, 2.0 * kPi * j / count, 2.0 * kPi * (j + 1) / count, g,
                    cut_levels, out);
  }
  return out;
}

bool sphere_touches(const geometry::Prism& body, const Vec3& lo, const Vec3& hi) {
  return std::any_of(body.spheres.begin(), body.spheres.end(), [&](const geometry::Sphere& s) {
    return reach(s, lo, hi).first < s.radius;
  });
}

void sphere_cell_points(const geometry::Prism& body, const Vec3& lo, const Vec3& hi, int order,
                        int cut_levels, const quadrature::CellSizing& sizing, SolidPoints& out) {
  const Vec3 half = 0.5 * (hi - lo), mid = lo + half;
  const BoundingBox plane{lo.head<2>(), hi.head<2>()};
  const bool coarse = sizing.spacing > 0.0 &&
                      (hi - lo).maxCoeff() > sizing.size_at(plane) * (1.0 + 1e-9);
  bool cut = false;
  for (const geometry::Sphere& s : body.spheres) {
    const auto [near, far] = reach(s, lo, hi);
    if (far <= s.radius) return; // the whole cell lies in a ball
    cut = cut || near < s.radius;
  }
  if (coarse || (cut && cut_levels > 0)) {
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner = lo + Vec3((k & 1) * half.x(), ((k >> 1) & 1) * half.y(),
                                    ((k >> 2) & 1) * half.z());
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
