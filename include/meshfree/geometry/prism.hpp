#pragma once
// Solid bodies of 3D Galerkin analyses: a plane body (polygon minus circular holes) extruded
// along z, minus spherical holes. A hole of the plane body is a cylindrical hole through the
// prism. Faces: each named boundary piece of the plane body (edge or hole) is a side face of that
// name, the ends are "back" (z = z0) and "front" (z = z0 + depth), and each sphere's surface is a
// face of the sphere's name.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include <string>
#include <vector>

namespace mf::geometry {

/// A spherical hole: the open ball of `radius` about `center` is not part of the body.
struct Sphere {
  Vec3 center{0.0, 0.0, 0.0};
  double radius = 0.0;
  std::string name;
  /// Signed distance from p to the sphere's surface (negative inside the ball).
  double distance(const Vec3& p) const { return (p - center).norm() - radius; }
};

struct Prism {
  Domain section = Domain::rectangle({0.0, 0.0}, {1.0, 1.0});
  double z0 = 0.0, depth = 1.0;
  std::vector<Sphere> spheres;

  /// True for points of the closed body: in the extruded section and in no sphere's open ball
  /// (points within `tol` times the body's size of a sphere's surface count as on it).
  bool contains(const Vec3& p, double tol = 1e-12) const {
    const double t = tol * std::max(1.0, depth);
    return p.z() >= z0 - t && p.z() <= z0 + depth + t && section.contains(p.head<2>(), tol) &&
           outside_spheres(p, tol);
  }
  /// True unless p lies inside some sphere by more than `tol` times the body's size.
  bool outside_spheres(const Vec3& p, double tol = 1e-12) const;
  double z1() const { return z0 + depth; }
  /// The largest of the depth and the section's extents.
  double size() const;
  /// Every face name: the section's edges and holes in order, "back" and "front", then the
  /// spheres.
  std::vector<std::string> face_names() const;
  /// What a face name given by a user selects: the face of that name, or, for a side of the
  /// bounding box named by its axis, the faces that lie wholly on it (x_min .. y_max as the
  /// section's Domain::names_selected; z_min the back, z_max the front). Empty when it selects
  /// nothing.
  std::vector<std::string> names_selected(const std::string& name) const;
};

/// Latitude rings about `spacing` apart in polar angle on a sphere of `radius`: an even count
/// (at least two), so that the equator is one.
int latitude_rings(double radius, double spacing);
/// Points on a circle of `circumference` about `spacing` apart: a multiple of four, at least four.
int ring_points(double circumference, double spacing);

/// Points on the part of `s`'s surface in the body, about `spacing` apart: latitude rings about
/// `spacing` apart in polar angle (an even count, so the equator is one), each ring's points a
/// multiple of four at even steps from phi = 0, so that a sphere centred on planes x = c_x or
/// y = c_y or z = c_z has points on them.
std::vector<Vec3> sphere_surface_points(const Prism& body, const Sphere& s, double spacing);

/// Points of the named face about `spacing` apart: a side face's pieces at round(length /
/// spacing) intervals times round(depth / spacing) intervals along z, an end's lattice of the
/// section's bounding box at round(size / spacing) intervals a side kept where it is in the
/// body, a sphere's rings (sphere_surface_points). Empty for an unknown name.
std::vector<Vec3> face_sample_points(const Prism& body, const std::string& face, double spacing);

/// Points of the body on the flat box [lo, hi] (one extent zero) at round(extent / spacing)
/// intervals along its other two axes.
std::vector<Vec3> plane_sample_points(const Prism& body, const Vec3& lo, const Vec3& hi,
                                      double spacing);

} // namespace mf::geometry
