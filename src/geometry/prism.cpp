#include "meshfree/geometry/prism.hpp"
#include <algorithm>

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

} // namespace mf::geometry
