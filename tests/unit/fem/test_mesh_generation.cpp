// Finite-element meshes made by gmsh from a problem's geometry: element types, nodes on the
// body and on the holes' arcs, the body's exact area, refinement boxes, errors.
#include "meshfree/core/error.hpp"
#include "meshfree/fem/elements.hpp"
#include "meshfree/fem/mesh_generation.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;
using fem::ElementType;

namespace {

/// The quarter of a 5 x 5 plate with a hole of radius 1 at the corner (the Kirsch problem).
geometry::Domain quarter_plate() {
  geometry::Domain d = geometry::Domain::rectangle({0.0, 0.0}, {5.0, 5.0});
  d.add_hole({{0.0, 0.0}, 1.0, "hole"});
  return d;
}

double mesh_area(const fem::Mesh& mesh) {
  const fem::PointShapes p = fem::domain_points(mesh, 4);
  double a = 0.0;
  for (double w : p.weight) a += w;
  return a;
}

/// Mean corner-to-corner edge length of the elements whose centroid lies in [lo, hi].
double mean_edge_in(const fem::Mesh& mesh, const Vec2& lo, const Vec2& hi) {
  const int corners = fem::corners_per_element(mesh.type);
  double sum = 0.0;
  int count = 0;
  for (int e = 0; e < mesh.element_count(); ++e) {
    Vec2 c = Vec2::Zero();
    for (int k = 0; k < corners; ++k) c += mesh.x[mesh.element(e)[k]] / corners;
    if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) continue;
    for (int k = 0; k < corners; ++k)
      sum += (mesh.x[mesh.element(e)[(k + 1) % corners]] - mesh.x[mesh.element(e)[k]]).norm();
    count += corners;
  }
  return sum / count;
}

} // namespace

TEST_CASE("gmsh meshes of a plate with a hole: types, nodes on the body and the arc, area",
          "[fem][gmsh]") {
  const geometry::Domain body = quarter_plate();
  const double exact_area = 25.0 - M_PI / 4.0;
  for (ElementType type : {ElementType::T3, ElementType::Q4, ElementType::Q8}) {
    CAPTURE(fem::element_name(type));
    const fem::Mesh mesh = fem::mesh_domain(body, 0.25, {}, type);
    REQUIRE(mesh.type == type);
    REQUIRE(mesh.element_count() > 300);
    for (int e = 0; e < mesh.element_count(); ++e) REQUIRE(fem::signed_area(mesh, e) > 0.0);
    int on_arc = 0;
    for (const Vec2& x : mesh.x) {
      REQUIRE(body.contains(x, 1e-9));
      if (std::abs(x.norm() - 1.0) < 1e-6) {
        REQUIRE(x.norm() == Approx(1.0).margin(1e-12));
        ++on_arc;
      }
    }
    // The arc of length pi/2 is cut into edges of about 0.25: at least 6 of them.
    REQUIRE(on_arc >= (type == ElementType::Q8 ? 13 : 7));
    const double area = mesh_area(mesh);
    if (type == ElementType::Q8) {
      // Mid-side nodes on the arc: each edge's quadratic misses the arc by O(theta^4) per unit
      // length (theta = 0.25 rad here), far below the chords' O(theta^2).
      REQUIRE(area == Approx(exact_area).epsilon(1e-6));
    } else {
      // Straight edges: the mesh is the polygon inscribed in the arc, short of the quarter disc
      // by sum (theta^3 / 12) r^2 over its chords, about theta^2 pi / 24 = 0.008 for theta = 0.25.
      const double missing = area - exact_area;
      REQUIRE(missing > 0.0);
      REQUIRE(missing < 0.02);
    }
  }
}

TEST_CASE("gmsh meshes: refinement boxes shrink the elements inside them", "[fem][gmsh]") {
  const geometry::Domain body = geometry::Domain::rectangle({0.0, 0.0}, {4.0, 2.0});
  geometry::Refinement box;
  box.box = BoundingBox{Vec2(0.0, 0.0), Vec2(1.0, 1.0)};
  box.spacing = 0.05;
  const fem::Mesh mesh = fem::mesh_domain(body, 0.2, {box}, ElementType::Q4);
  const double inside = mean_edge_in(mesh, {0.0, 0.0}, {0.9, 0.9});
  const double outside = mean_edge_in(mesh, {2.5, 0.0}, {4.0, 2.0});
  CHECK(inside == Approx(0.05).epsilon(0.3));
  CHECK(outside == Approx(0.2).epsilon(0.3));
  REQUIRE(mesh_area(mesh) == Approx(8.0).epsilon(1e-12));
}

TEST_CASE("gmsh meshes: a polygon and a hole inside it, the same mesh twice", "[fem][gmsh]") {
  geometry::Domain body =
      geometry::Domain::polygon({{0.0, 0.0}, {48.0, 44.0}, {48.0, 60.0}, {0.0, 44.0}});
  body.add_hole({{24.0, 40.0}, 4.0, "hole"});
  const fem::Mesh a = fem::mesh_domain(body, 2.0, {}, ElementType::Q8);
  const fem::Mesh b = fem::mesh_domain(body, 2.0, {}, ElementType::Q8);
  // Cook's membrane (a trapezoid of area 1440) minus a disc; edges of 2 on the radius 4 span
  // theta = 0.5 rad, so the quadratic arcs are 16 times less exact than above.
  REQUIRE(mesh_area(a) == Approx(1440.0 - M_PI * 16.0).epsilon(1e-5));
  REQUIRE(a.connectivity == b.connectivity);
  REQUIRE(a.x == b.x);
}

TEST_CASE("gmsh meshes: a body the holes swallow is an error", "[fem][gmsh]") {
  geometry::Domain body = geometry::Domain::rectangle({0.0, 0.0}, {1.0, 1.0});
  body.add_hole({{0.5, 0.5}, 2.0, "hole"});
  REQUIRE_THROWS_AS(fem::mesh_domain(body, 0.1, {}, ElementType::T3), Error);
}
