#include "meshfree/geometry/prism.hpp"
#include <algorithm>
#include <cmath>

namespace mf::geometry {

bool Prism::outside_spheres(const Vec3& p, double tol) const {
  const double t = tol * size();
  return std::none_of(spheres.begin(), spheres.end(),
                      [&](const Sphere& s) { return s.distance(p) < -t; });
}

double Prism::size() const {
  return std::max(depth, section.bounds().size().maxCoeff());
}

std::vector<std::string> Prism::face_names() const {
  std::vector<std::string> names;
  for (const Curve& c : section.boundary())
    if (std::find(names.begin(), names.end(), c.name) == names.end()) names.push_back(c.name);
  names.push_back("back");
  names.push_back("front");
  for (const Sphere& s : spheres) names.push_back(s.name);
  return names;
}

std::vector<std::string> Prism::names_selected(const std::string& name) const {
  const std::vector<std::string> all = face_names();
  if (std::find(all.begin(), all.end(), name) != all.end()) return {name};
  if (name == "z_min") return {"back"};
  if (name == "z_max") return {"front"};
  return section.names_selected(name);
}

namespace {

constexpr double kPi = 3.14159265358979323846;

int intervals(double length, double spacing) {
  return std::max(1, static_cast<int>(std::lround(length / spacing)));
}

/// The points lo + (i / n1) e1 + (j / n2) e2 of the body, for the grid's two axes a1 and a2.
std::vector<Vec3> grid_in_body(const Prism& body, const Vec3& lo, const Vec3& hi, int a1, int a2,
                               double spacing) {
  const int n1 = intervals(hi(a1) - lo(a1), spacing), n2 = intervals(hi(a2) - lo(a2), spacing);
  std::vector<Vec3> out;
  for (int j = 0; j <= n2; ++j)
    for (int i = 0; i <= n1; ++i) {
      Vec3 x = lo;
      x(a1) += (hi(a1) - lo(a1)) * i / n1;
      x(a2) += (hi(a2) - lo(a2)) * j / n2;
      if (body.contains(x, 1e-9)) out.push_back(x);
    }
  return out;
}

} // namespace

int latitude_rings(double radius, double spacing) {
  const int n = std::max(2, static_cast<int>(std::lround(kPi * radius / spacing)));
  return n + n % 2;
}

int ring_points(double circumference, double spacing) {
  return 4 * std::max(1, static_cast<int>(std::lround(circumference / (4.0 * spacing))));
}

std::vector<Vec3> sphere_surface_points(const Prism& body, const Sphere& s, double spacing) {
  const int rings = latitude_rings(s.radius, spacing);
  std::vector<Vec3> out;
  for (int i = 0; i <= rings; ++i) {
    const double theta = kPi * i / rings;
    const double rho = s.radius * std::sin(theta), z = s.radius * std::cos(theta);
    const int count = (i == 0 || i == rings) ? 1 : ring_points(2.0 * kPi * rho, spacing);
    for (int j = 0; j < count; ++j) {
      const double phi = 2.0 * kPi * j / count;
      const Vec3 x = s.center + Vec3(rho * std::cos(phi), rho * std::sin(phi), z);
      if (body.contains(x, 1e-9)) out.push_back(x);
    }
  }
  return out;
}

std::vector<Vec3> face_sample_points(const Prism& body, const std::string& face, double spacing) {
  for (const Sphere& s : body.spheres)
    if (s.name == face) return sphere_surface_points(body, s, spacing);
  if (face == "back" || face == "front") {
    const BoundingBox b = body.section.bounds();
    const double z = face == "back" ? body.z0 : body.z1();
    return grid_in_body(body, Vec3(b.lo.x(), b.lo.y(), z), Vec3(b.hi.x(), b.hi.y(), z), 0, 1,
                        spacing);
  }
  std::vector<Vec3> out;
  const int layers = intervals(body.depth, spacing);
  for (const Curve& c : body.section.boundary()) {
    if (c.name != face) continue;
    const int n = intervals(c.length(), spacing);
    for (int k = 0; k <= layers; ++k)
      for (int i = 0; i <= n; ++i) {
        const Vec2 xy = c.point(static_cast<double>(i) / n);
        const Vec3 x(xy.x(), xy.y(), body.z0 + body.depth * k / layers);
        if (body.contains(x, 1e-9)) out.push_back(x);
      }
  }
  return out;
}

std::vector<Vec3> plane_sample_points(const Prism& body, const Vec3& lo, const Vec3& hi,
                                      double spacing) {
  int flat = 0;
  (hi - lo).cwiseAbs().minCoeff(&flat);
  return grid_in_body(body, lo, hi, (flat + 1) % 3, (flat + 2) % 3, spacing);
}

} // namespace mf::geometry
