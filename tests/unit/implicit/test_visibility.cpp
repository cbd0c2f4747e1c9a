// The visibility criterion (MeshfreeSpace::hide_behind_holes): a segment is crossed by a
// boundary piece only where it passes through it with both ends off it (a segment, slanted or
// not, or an arc within its sweep); over a plate with an edge notch narrower than the supports,
// no node on one side of the notch covers a point on the other, every point of the body still
// has shape functions that reproduce 1 and x, and away from the notch the supports are those
// without the criterion; a body without holes of an outline (a slanted convex polygon, a plate
// with a circular hole) keeps every support.
#include "meshfree/quadrature/integration_points.hpp"
#include "shape_reproduction.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

using namespace mf;
using geometry::Curve;

namespace {

/// A body's cloud at spacing h, its points' supports without and with the criterion, and the
/// space that hides nodes behind the body's holes.
struct Supports {
  geometry::NodeCloud cloud;
  std::vector<Vec2> points;
  implicit::Csr plain, hidden;
  std::unique_ptr<implicit::MeshfreeSpace> seeing;
};

Supports supports(const geometry::Domain& body, double h) {
  kernels::ShapeSettings shape;
  shape.dim = 2;
  Supports s;
  s.cloud = geometry::generate_nodes(body, h, {});
  s.points = quadrature::domain_points(body, h, 3, 2).x;
  s.plain = implicit::MeshfreeSpace(s.cloud, shape, Vec2(2, 2)).support_lists(s.points);
  s.seeing = std::make_unique<implicit::MeshfreeSpace>(s.cloud, shape, Vec2(2, 2));
  s.seeing->hide_behind_holes(body);
  s.hidden = s.seeing->support_lists(s.points);
  return s;
}

} // namespace

TEST_CASE("visibility: a curve stands between two points only when crossed inside both",
          "[visibility][geometry]") {
  Curve wall;
  wall.a = Vec2(0.0, -1.0);
  wall.b = Vec2(0.0, 1.0);
  const double tol = 1e-9;
  CHECK(wall.crossed_by({-1.0, 0.0}, {1.0, 0.0}, tol));
  CHECK_FALSE(wall.crossed_by({-1.0, 0.0}, {-0.5, 0.0}, tol)); // stops short
  CHECK_FALSE(wall.crossed_by({-1.0, 0.0}, {0.0, 0.0}, tol));  // ends on it
  CHECK_FALSE(wall.crossed_by({0.0, 0.5}, {1.0, 0.5}, tol));   // starts on it
  CHECK_FALSE(wall.crossed_by({-1.0, 2.0}, {1.0, 2.0}, tol));  // passes beyond its end
  CHECK_FALSE(wall.crossed_by({0.0, -2.0}, {0.0, 2.0}, tol));  // along it
  // A slanted piece: points on it (rounded off it by 1e-16) never stand on either side of it.
  Curve slant;
  slant.a = Vec2(0.0, 0.0);
  slant.b = Vec2(48.0, 44.0);
  int crossed = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j)
      crossed += slant.crossed_by(slant.point(i / 40.0), slant.point(j / 40.0), tol);
  CHECK(crossed == 0);
  CHECK(slant.crossed_by({30.0, 20.0}, {20.0, 30.0}, tol));
  Curve arc; // the upper half of the unit circle
  arc.kind = Curve::Kind::Arc;
  arc.center = Vec2(0.0, 0.0);
  arc.radius = 1.0;
  arc.theta0 = 0.0;
  arc.theta1 = std::acos(-1.0);
  CHECK(arc.crossed_by({0.0, 0.0}, {0.0, 2.0}, tol));
  CHECK_FALSE(arc.crossed_by({0.0, 0.0}, {0.0, -2.0}, tol)); // the circle, not the arc
  CHECK(arc.crossed_by({-2.0, 0.5}, {2.0, 0.5}, tol));
  CHECK_FALSE(arc.crossed_by({-0.5, 0.5}, {0.5, 0.5}, tol)); // inside the circle
}

TEST_CASE("visibility: supports do not reach across a notch narrower than themselves",
          "[visibility][implicit]") {
  geometry::Domain plate = geometry::Domain::rectangle({0.0, 0.0}, {20.0, 20.0});
  plate.add_hole(geometry::OutlineHole::polygon({{-1, 9.95}, {8, 9.95}, {8, 10.05}, {-1, 10.05}},
                                                "notch"));
  const Supports s = supports(plate, 0.25);
  const std::vector<Vec2>& points = s.points;
  const implicit::Csr &hidden = s.hidden, &all = s.plain;
  int across_plain = 0, across = 0, changed_far = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Vec2& x = points[p];
    const auto across_notch = [&](int I) {
      const Vec2& y = s.cloud.x[I];
      return (x.y() - 10.0) * (y.y() - 10.0) < 0.0 && std::abs(x.y() - 10.0) > 0.05 - 1e-12 &&
             std::abs(y.y() - 10.0) > 0.05 - 1e-12 && std::max(x.x(), y.x()) < 7.5;
    };
    for (int k = all.offset[p]; k < all.offset[p + 1]; ++k) across_plain += across_notch(all.index[k]);
    for (int k = hidden.offset[p]; k < hidden.offset[p + 1]; ++k) across += across_notch(hidden.index[k]);
    const bool far = (x - Vec2(8.0, 10.0)).norm() > 1.0 && std::abs(x.y() - 10.0) > 1.0;
    if (far && (hidden.size(p) != all.size(p))) ++changed_far;
  }
  CHECK(across_plain > 1000); // the plain supports tie the notch's faces
  CHECK(across == 0);
  CHECK(changed_far == 0);
  CHECK(linear_reproduction_error(*s.seeing, points) < 1e-10);
}

TEST_CASE("visibility: bodies without holes of an outline keep every support",
          "[visibility][implicit]") {
  geometry::Domain cook = geometry::Domain::polygon({{0, 0}, {48, 44}, {48, 60}, {0, 44}});
  geometry::Domain kirsch = geometry::Domain::rectangle({0.0, 0.0}, {5.0, 5.0});
  kirsch.add_hole(geometry::Circle{{0.0, 0.0}, 1.0, "hole"});
  for (const auto& [body, h] : {std::pair{cook, 2.0}, std::pair{kirsch, 0.2}}) {
    const Supports s = supports(body, h);
    const implicit::Csr &a = s.plain, &b = s.hidden;
    CHECK(a.offset == b.offset);
    CHECK(a.index == b.index);
  }
}
