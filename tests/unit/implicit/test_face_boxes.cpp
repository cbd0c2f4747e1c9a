// A boundary condition's `box` on the faces of a 3D body (implicit/solid_points, solid_fe): the
// meshfree face points integrate exactly the part of the named faces inside the box, wherever
// its edges fall among the background cells (a table over spacings that do and do not divide
// the box), on side faces, end faces, a hole's face and a polygon's end; with the partition of
// unity of the shape functions, the force a pressure there carries is p times that area. Finite
// elements take a box whose edges follow element borders and refuse one that cuts an element.
#include "meshfree/core/error.hpp"
#include "meshfree/geometry/box_clip.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/solid_bricks.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

namespace {

double area(const geometry::Prism& body, double spacing, const std::string& face,
            const spec::Box& box) {
  spec::DiscretisationSpec d;
  d.spacing = d.cell_size = spacing;
  d.cut_arcs = true;
  double sum = 0.0;
  for (double w : implicit::prism_face_points(body, d, {face}, box).weight) sum += w;
  return sum;
}

spec::Box box(const Vec3& lo, const Vec3& hi) {
  return spec::Box{lo, hi};
}

} // namespace

TEST_CASE("face boxes: the loaded area is the box's part of the face at any spacing",
          "[solid3d][boundary]") {
  const geometry::Prism block{geometry::Domain::rectangle({0.0, 0.0}, {10.0, 10.0}), 0.0, 10.0, {}};
  // A 4 x 4 patch on the top side (y = 10) and on the front end (z = 10), boxes whose edges
  // fall inside cells at every spacing but 1 and 2/3; a box reaching past the body's edge.
  for (double h : {1.0, 0.75, 0.7, 2.0 / 3.0, 0.6, 1.3}) {
    CAPTURE(h);
    CHECK(area(block, h, "top", box({3, 9.5, 3}, {7, 11, 7})) == Approx(16.0).epsilon(1e-12));
    CHECK(area(block, h, "front", box({3, 3, 9}, {7, 7, 11})) == Approx(16.0).epsilon(1e-12));
    CHECK(area(block, h, "top", box({-1, 9, 8.2}, {2.3, 11, 12})) ==
          Approx(2.3 * 1.8).epsilon(1e-12));
    CHECK(area(block, h, "front", box({8.65, -1, 0}, {11, 4.35, 10})) ==
          Approx(1.35 * 4.35).epsilon(1e-12));
  }
  // A box that misses the face loads nothing.
  CHECK(area(block, 1.0, "top", box({3, 0, 3}, {7, 9, 7})) == 0.0);
}

TEST_CASE("face boxes: a hole's face cut by a box", "[solid3d][boundary]") {
  geometry::Domain plate = geometry::Domain::rectangle({0.0, 0.0}, {10.0, 10.0});
  plate.add_hole({Vec2(5.0, 5.0), 1.5, "hole"});
  const geometry::Prism holed{plate, 0.0, 4.0, {}};
  // The half of the hole's face with x >= 5.4, z in [1, 3.3]: the arc 2 r acos(0.4 / r) long.
  const double arc = 2.0 * 1.5 * std::acos(0.4 / 1.5);
  for (double h : {1.0, 0.7, 0.45}) {
    CAPTURE(h);
    CHECK(area(holed, h, "hole", box({5.4, 0, 1}, {20, 20, 3.3})) ==
          Approx(arc * 2.3).epsilon(1e-11));
  }
}

TEST_CASE("face boxes: polygons clipped to a box exactly", "[solid3d][boundary]") {
  const auto area = [](const std::vector<Vec2>& v) { return std::abs(geometry::signed_area(v)); };
  // A trapezoid's part with y in [1, 3], x in [5, 9]: under its slanted edge x = 8 - y / 2, a
  // trapezoid of widths 2.5 and 1.5 over y from 1 to 3.
  const std::vector<Vec2> trapezoid{{0, 0}, {8, 0}, {6, 4}, {2, 4}};
  const std::vector<Vec2> cut = geometry::clip_polygon(trapezoid, {{5, 1}, {9, 3}});
  CHECK(cut.size() == 4);
  CHECK(area(cut) == Approx(4.0).epsilon(1e-15));
  // An L's corner: a connected part of a concave polygon; a box holding it whole; a box off it.
  const std::vector<Vec2> ell{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  CHECK(area(geometry::clip_polygon(ell, {{0.5, 0.5}, {2, 2}})) == Approx(1.25).epsilon(1e-15));
  CHECK(area(geometry::clip_polygon(ell, {{-1, -1}, {5, 5}})) == Approx(7.0).epsilon(1e-15));
  CHECK(geometry::clip_polygon(ell, {{2, 2}, {3, 3}}).size() < 3);
  // The segment from (0, 0) to (4, 2) in [1, 3] x [0, 5]: t in [1/4, 3/4]; along a side.
  const auto t = geometry::clip_segment({0, 0}, {4, 2}, {{1, 0}, {3, 5}}, 1e-12);
  REQUIRE(t);
  CHECK(t->first == 0.25);
  CHECK(t->second == 0.75);
  CHECK(geometry::clip_segment({0, 5}, {4, 5}, {{1, 0}, {3, 5}}, 1e-12));
  CHECK_FALSE(geometry::clip_segment({0, 6}, {4, 6}, {{1, 0}, {3, 5}}, 1e-12));
}

TEST_CASE("face boxes: finite elements take boxes on element borders and refuse the others",
          "[solid3d][boundary][fem]") {
  const geometry::Prism block{geometry::Domain::rectangle({0.0, 0.0}, {10.0, 10.0}), 0.0, 10.0, {}};
  for (const char* element : {"q4", "q8"}) {
    CAPTURE(element);
    spec::DiscretisationSpec d;
    d.method = spec::Method::Fem;
    d.fem.element = element;
    d.spacing = d.cell_size = 1.0;
    const implicit::ExtrudedMesh fe(implicit::plane_fe_mesh(d, block.section), block, 1.0, {});
    double sum = 0.0;
    for (double w : fe.face_points({"top"}, 2, box({3, 9.5, 3}, {7, 11, 7})).points.weight)
      sum += w;
    CHECK(sum == Approx(16.0).epsilon(1e-12));
    CHECK_THROWS_WITH(fe.face_points({"top"}, 2, box({3.5, 9.5, 3}, {7, 11, 7})),
                      Catch::Contains("the box cuts the element face") &&
                          Catch::Contains("a box's edges must lie on element borders"));
    CHECK_THROWS_WITH(fe.face_points({"front"}, 2, box({3, 3, 9}, {7, 7.25, 11})),
                      Catch::Contains("element borders"));
  }
}
