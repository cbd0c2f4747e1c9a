// Holes of any closed outline (geometry::OutlineHole): polygons, rectangles and slots, alone, at
// any angle, crossing the plate's outline or another hole (then their union is left out). For
// each the body's boundary has the exact length and outward normals, points in the hole are
// outside the body, the distance to the boundary and a vertical line's crossings are exact, the
// integration points converge to the exact area, and the nodes' shape functions are defined
// everywhere and reproduce a linear field.
#include "boundary_walk.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include "shape_reproduction.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

using namespace mf;

namespace {

const double pi = std::acos(-1.0);

struct Case {
  const char* what;
  std::vector<geometry::OutlineHole> holes;
  double area;      // of the plate [0, 2] x [0, 1] less its holes
  double perimeter; // of the body's whole boundary
};

geometry::OutlineHole slot(Vec2 a, Vec2 b, double half) {
  return geometry::OutlineHole::slot(a, b, half, "h");
}
geometry::OutlineHole poly(std::vector<Vec2> v) {
  return geometry::OutlineHole::polygon(v, "h");
}

std::vector<Case> cases() {
  const double l = std::hypot(0.3, 0.4);                     // the inclined slot's axis
  const double tri = 0.5 * 0.2 * 0.3;                        // triangle (0.9,0.2)(1.1,0.2)(1,0.5)
  const double tri_edges = 0.2 + 2.0 * std::hypot(0.1, 0.3); // its edges
  return {
      {"a slot at 53 degrees",
       {slot({0.6, 0.3}, {0.9, 0.7}, 0.1)},
       2.0 - (0.2 * l + pi * 0.01),
       6.0 + 2.0 * l + 2.0 * pi * 0.1},
      {"a slot along x",
       {slot({0.5, 0.5}, {1.5, 0.5}, 0.2)},
       2.0 - (0.4 + pi * 0.04),
       6.0 + 2.0 + 2.0 * pi * 0.2},
      {"a slot of no length (a circle)",
       {slot({1.0, 0.5}, {1.0, 0.5}, 0.25)},
       2.0 - pi * 0.0625,
       6.0 + 2.0 * pi * 0.25},
      {"a rectangle",
       {poly({{0.5, 0.25}, {1.25, 0.25}, {1.25, 0.75}, {0.5, 0.75}})},
       2.0 - 0.375,
       6.0 + 2.5},
      {"a triangle given clockwise",
       {poly({{0.9, 0.2}, {1.0, 0.5}, {1.1, 0.2}})},
       2.0 - tri,
       6.0 + tri_edges},
      {"a notch through the bottom edge",
       {poly({{0.9, -0.5}, {1.1, -0.5}, {1.1, 0.4}, {0.9, 0.4}})},
       2.0 - 0.2 * 0.4,
       6.0 - 0.2 + 0.2 + 2.0 * 0.4},
      // The slot's end round b and its last 0.2 lie in the rectangle: the union's area and
      // outline (the rectangle's less its left edge's 0.2 inside the slot, the slot's sides up
      // to x = 0.8 and its end round a).
      {"a slot into a rectangle",
       {slot({0.5, 0.5}, {1.0, 0.5}, 0.1), poly({{0.8, 0.3}, {1.2, 0.3}, {1.2, 0.7}, {0.8, 0.7}})},
       2.0 - (0.1 + pi * 0.01 + 0.16 - 0.04 - 0.5 * pi * 0.01),
       6.0 + 1.4 + 0.6 + pi * 0.1},
      {"a slot and a triangle",
       {slot({0.3, 0.5}, {0.6, 0.5}, 0.15), poly({{0.9, 0.2}, {1.1, 0.2}, {1.0, 0.5}})},
       2.0 - (0.09 + pi * 0.0225) - tri,
       6.0 + 0.6 + 2.0 * pi * 0.15 + tri_edges},
  };
}

geometry::Domain plate_with(const std::vector<geometry::OutlineHole>& holes) {
  geometry::Domain d = geometry::Domain::rectangle({0, 0}, {2, 1});
  for (const auto& h : holes) d.add_hole(h);
  return d;
}

} // namespace

TEST_CASE("outline holes: the boundary's length and normals, membership and distance",
          "[geometry][holes]") {
  for (const Case& c : cases()) {
    CAPTURE(c.what);
    const geometry::Domain d = plate_with(c.holes);
    const double length = walk_boundary(d);
    CHECK(length == Approx(c.perimeter).epsilon(1e-9));
    for (const auto& h : c.holes) {
      const BoundingBox b = h.bounds();
      const Vec2 inside =
          h.kind == geometry::OutlineHole::Kind::Slot
              ? Vec2(0.5 * (h.a + h.b))
              : Vec2(std::accumulate(h.vertices.begin(), h.vertices.end(), Vec2(Vec2::Zero())) /
                     static_cast<double>(h.vertices.size()));
      CHECK_FALSE(d.contains(inside));
      CHECK(b.contains(inside));
      CHECK(std::abs(h.area()) > 0.0);
    }
  }
}

TEST_CASE("outline holes: a vertical line's crossings bound the body's parts",
          "[geometry][holes]") {
  // Along x = 0.75 the inclined slot's sides are crossed where the line meets them; the body's
  // length along the line is the plate's less the slot's chord, checked by sampling.
  for (const Case& c : cases()) {
    CAPTURE(c.what);
    const geometry::Domain d = plate_with(c.holes);
    for (const double x : {0.55, 0.75, 0.95, 1.0, 1.3}) {
      std::vector<double> ys{0.0, 1.0};
      d.hole_crossings(x, ys);
      std::sort(ys.begin(), ys.end());
      double between = 0.0; // length inside the body from the crossings: midpoints decide
      for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
        const double lo = std::max(ys[k], 0.0), hi = std::min(ys[k + 1], 1.0);
        if (hi > lo && d.contains(Vec2(x, 0.5 * (lo + hi)))) between += hi - lo;
      }
      constexpr int n = 200000;
      double sampled = 0.0;
      for (int k = 0; k < n; ++k) sampled += d.contains(Vec2(x, (k + 0.5) / n)) ? 1.0 / n : 0.0;
      CHECK(between == Approx(sampled).margin(2e-5));
    }
  }
}

TEST_CASE("outline holes: integration points converge to the body's area", "[geometry][holes]") {
  // Cells the holes cut are split (cut_levels), as for a polygon's own edges: the area's error
  // falls about fourfold a level (first order in the cut cells' size along the boundary).
  for (const Case& c : cases()) {
    CAPTURE(c.what);
    const geometry::Domain d = plate_with(c.holes);
    double previous = 1e300;
    for (const int levels : {2, 4, 6}) {
      const quadrature::DomainPoints q = quadrature::domain_points(d, 0.1, 3, levels);
      const double area = std::accumulate(q.weight.begin(), q.weight.end(), 0.0);
      const double error = std::abs(area - c.area) / c.area;
      CHECK(error < 0.6 * previous + 1e-12);
      previous = error;
    }
    CHECK(previous < 2e-4);
  }
}

TEST_CASE("outline holes: the nodes' shape functions exist in the body and reproduce a linear "
          "field",
          "[geometry][holes]") {
  for (const Case& c : cases())
    for (const double h : {0.05, 0.07}) {
      CAPTURE(c.what, h);
      const CloudCheck k = check_cloud(plate_with(c.holes), h);
      CHECK(k.outside == 0);
      CHECK(k.reproduction < 1e-10);
    }
}

TEST_CASE("outline holes: a polygon that crosses itself or has no area is refused",
          "[geometry][holes]") {
  CHECK_THROWS_WITH(geometry::OutlineHole::polygon({{0, 0}, {2, 1}, {2, 0}, {0, 1.5}}),
                    Catch::Contains("must not cross itself"));
  CHECK_THROWS_WITH(geometry::OutlineHole::polygon({{0, 0}, {1, 1}, {2, 2}}),
                    Catch::Contains("zero area"));
  CHECK_THROWS_WITH(geometry::OutlineHole::slot({0, 0}, {1, 0}, 0.0),
                    Catch::Contains("width must be positive"));
}
