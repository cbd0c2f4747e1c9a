// Rounded corners of a plane body (geometry::Fillet): convex and re-entrant corners, acute and
// obtuse, a whole edge taken by two fillets (a rounded end), beside a hole. For each the outline
// has the exact length, bounds and outward normals (a circular arc tangent to both edges), points
// between a corner and its arc are in the body or not as the rounding says, the distance to the
// boundary and a vertical line's crossings are exact, the integration points converge to the exact
// area, and the nodes' shape functions are defined everywhere and reproduce a linear field.
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

struct Rounding {
  Vec2 at;
  double radius;
};

struct Case {
  const char* what;
  std::vector<Vec2> polygon;
  std::vector<Rounding> fillets;
  double area;      // closed form
  double perimeter; // of the whole boundary
  BoundingBox bounds;
  Vec2 cut_off; // a point the rounding removes (or NaN)
  Vec2 added;   // a point the rounding adds (or NaN)
};

const Vec2 none(std::nan(""), std::nan(""));

std::vector<Case> cases() {
  // A quarter-circle fillet of radius r at a right angle removes or adds (1 - pi / 4) r^2 and
  // shortens the outline by (2 - pi / 2) r.
  const auto quarter_area = [](double r) { return (1.0 - 0.25 * pi) * r * r; };
  const auto quarter_length = [](double r) { return (2.0 - 0.5 * pi) * r; };
  // The triangle (0,0) (2,0) (0,1): at (2,0) its angle is alpha = atan(1/2), the fillet's tangent
  // length r / tan(alpha / 2) and its arc r (pi - alpha).
  const double alpha = std::atan(0.5), r = 0.1, t = r / std::tan(0.5 * alpha);
  const Vec2 rect[] = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const std::vector<Vec2> l_shape{{0, 0}, {2, 0}, {2, 0.5}, {0.5, 0.5}, {0.5, 2}, {0, 2}};
  return {
      {"a rectangle with its four corners rounded",
       {rect[0], rect[1], rect[2], rect[3]},
       {{rect[0], 0.2}, {rect[1], 0.2}, {rect[2], 0.2}, {rect[3], 0.2}},
       2.0 - 4.0 * quarter_area(0.2),
       6.0 - 4.0 * quarter_length(0.2),
       {{0, 0}, {2, 1}},
       {0.02, 0.02},
       none},
      {"an L-bracket: a fillet in its re-entrant corner and one outside",
       l_shape,
       {{{0.5, 0.5}, 0.25}, {{2, 0}, 0.3}},
       1.75 + quarter_area(0.25) - quarter_area(0.3),
       8.0 - quarter_length(0.25) - quarter_length(0.3),
       {{0, 0}, {2, 2}},
       {1.98, 0.02},
       {0.55, 0.55}},
      {"an acute corner of a triangle",
       {{0, 0}, {2, 0}, {0, 1}},
       {{{2, 0}, r}},
       1.0 - (r * t - 0.5 * r * r * (pi - alpha)),
       3.0 + std::sqrt(5.0) - 2.0 * t + r * (pi - alpha),
       {{0, 0}, {2.0 - t + r, 1.0}}, // the arc passes due east of its centre
       {1.99, 0.001},
       none},
      {"a rounded end: the right edge taken whole by two fillets",
       {rect[0], rect[1], rect[2], rect[3]},
       {{rect[1], 0.5}, {rect[2], 0.5}},
       2.0 - 2.0 * quarter_area(0.5),
       6.0 - 2.0 * quarter_length(0.5),
       {{0, 0}, {2, 1}},
       {1.95, 0.05},
       none},
  };
}

geometry::Domain body_of(const Case& c, bool with_hole = false) {
  geometry::Domain d = geometry::Domain::polygon(c.polygon);
  for (const Rounding& f : c.fillets) d.round_corner(f.at, f.radius);
  if (with_hole) d.add_hole(geometry::Circle{{0.25, 0.25}, 0.1, "hole"});
  return d;
}

} // namespace

TEST_CASE("fillets: the outline's length, bounds and normals, membership and distance",
          "[geometry][fillets]") {
  for (const Case& c : cases()) {
    CAPTURE(c.what);
    const geometry::Domain d = body_of(c);
    const double length = walk_boundary(d, true);
    CHECK(length == Approx(c.perimeter).epsilon(1e-12));
    // The pieces join (a closed loop) and an arc is tangent to the pieces it joins.
    const auto& outline = d.outline();
    for (std::size_t k = 0; k < outline.size(); ++k) {
      const geometry::Curve& a = outline[k];
      const geometry::Curve& b = outline[(k + 1) % outline.size()];
      CHECK((a.point(1.0) - b.point(0.0)).norm() < 1e-12);
      if (a.kind == geometry::Curve::Kind::Arc || b.kind == geometry::Curve::Kind::Arc)
        CHECK((a.outward_normal(1.0) - b.outward_normal(0.0)).norm() < 1e-9);
    }
    CHECK((d.bounds().lo - c.bounds.lo).norm() < 1e-12);
    CHECK((d.bounds().hi - c.bounds.hi).norm() < 1e-12);
    CHECK(d.area_estimate() == Approx(c.area).epsilon(1e-12));
    if (!std::isnan(c.cut_off.x())) CHECK_FALSE(d.contains(c.cut_off));
    if (!std::isnan(c.added.x())) CHECK(d.contains(c.added));
  }
}

TEST_CASE("fillets: a vertical line's crossings bound the body's parts", "[geometry][fillets]") {
  for (const Case& c : cases()) {
    CAPTURE(c.what);
    const geometry::Domain d = body_of(c, true);
    const BoundingBox b = d.bounds();
    for (const double f : {0.01, 0.1, 0.25, 0.3, 0.49, 0.9, 0.97, 0.995}) {
      const double x = b.lo.x() + f * b.size().x();
      std::vector<double> ys;
      d.outline_crossings(x, ys);
      d.hole_crossings(x, ys);
      std::sort(ys.begin(), ys.end());
      double between = 0.0; // the body's length along the line from the crossings
      for (std::size_t k = 0; k + 1 < ys.size(); ++k)
        if (d.contains(Vec2(x, 0.5 * (ys[k] + ys[k + 1])))) between += ys[k + 1] - ys[k];
      constexpr int n = 200000;
      double sampled = 0.0;
      for (int k = 0; k < n; ++k)
        sampled += d.contains(Vec2(x, b.lo.y() + (k + 0.5) / n * b.size().y())) ? 1.0 / n : 0.0;
      CAPTURE(x);
      CHECK(between == Approx(sampled * b.size().y()).margin(2e-5 * b.size().y()));
    }
  }
}

TEST_CASE("fillets: integration points converge to the body's area", "[geometry][fillets]") {
  for (const Case& c : cases()) {
    CAPTURE(c.what);
    const geometry::Domain d = body_of(c);
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

TEST_CASE("fillets: the nodes' shape functions exist in the body and reproduce a linear field",
          "[geometry][fillets]") {
  for (const Case& c : cases())
    for (const double h : {0.05, 0.07}) {
      CAPTURE(c.what, h);
      const CloudCheck k = check_cloud(body_of(c, true), h);
      CHECK(k.outside == 0);
      CHECK(k.reproduction < 1e-10);
    }
}

TEST_CASE("fillets: a corner that is not there, straight, rounded twice or too small is refused",
          "[geometry][fillets]") {
  geometry::Domain d = geometry::Domain::polygon({{0, 0}, {2, 0}, {3, 0}, {3, 1}, {0, 1}});
  CHECK_THROWS_WITH(d.round_corner({1, 0}, 0.1), Catch::Contains("no corner of the outline"));
  CHECK_THROWS_WITH(d.round_corner({2, 0}, 0.1), Catch::Contains("is straight"));
  CHECK_THROWS_WITH(d.round_corner({0, 0}, -0.1), Catch::Contains("must be positive"));
  CHECK_THROWS_WITH(d.round_corner({3, 1}, 1.5), Catch::Contains("needs 1.5 of edge"));
  d.round_corner({3, 1}, 0.6);
  CHECK_THROWS_WITH(d.round_corner({3, 1}, 0.1), Catch::Contains("rounded already"));
  CHECK_THROWS_WITH(d.round_corner({3, 0}, 0.5), Catch::Contains("needs 1.1 of edge"));
  d.round_corner({3, 0}, 0.4); // 0.4 + 0.6 take the whole edge: allowed
  CHECK(d.outline().size() == 6u);
}
