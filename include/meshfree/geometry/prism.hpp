#pragma once
// Solid bodies of 3D Galerkin analyses: a plane body (polygon minus circular holes) extruded
// along z. A hole of the plane body is a cylindrical hole through the prism. Faces: each named
// boundary piece of the plane body (edge or hole) is a side face of that name, and the ends are
// "back" (z = z0) and "front" (z = z0 + depth).
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include <string>
#include <vector>

namespace mf::geometry {

struct Prism {
  Domain section = Domain::rectangle({0.0, 0.0}, {1.0, 1.0});
  double z0 = 0.0, depth = 1.0;

  bool contains(const Vec3& p, double tol = 1e-12) const {
    const double t = tol * std::max(1.0, depth);
    return p.z() >= z0 - t && p.z() <= z0 + depth + t && section.contains(p.head<2>(), tol);
  }
  double z1() const { return z0 + depth; }
  /// Every face name: the section's edges and holes in order, then "back" and "front".
  std::vector<std::string> face_names() const;
};

} // namespace mf::geometry
