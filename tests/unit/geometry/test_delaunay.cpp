// Triangles through plane points (geometry/delaunay): the Delaunay triangulation of degenerate
// and random points, and the part of it in a body over the bodies and clouds a user gives.
#include "meshfree/geometry/delaunay.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

using namespace mf;
using geometry::Triangle;

namespace {

double signed_area(const std::vector<Vec2>& x, const Triangle& t) {
  const Vec2 a = x[t[1]] - x[t[0]], b = x[t[2]] - x[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

/// The sum of the triangles' areas; fails a check where one is not counter-clockwise.
double covered_area(const std::vector<Vec2>& x, const std::vector<Triangle>& tri) {
  double sum = 0.0;
  int clockwise = 0;
  for (const Triangle& t : tri) {
    const double a = signed_area(x, t);
    clockwise += a <= 0.0;
    sum += a;
  }
  CHECK(clockwise == 0);
  return sum;
}

/// The number of points that are a vertex of no triangle.
int unused_points(std::size_t n, const std::vector<Triangle>& tri) {
  std::vector<char> used(n, 0);
  for (const Triangle& t : tri)
    for (int v : t) used[v] = 1;
  return static_cast<int>(std::count(used.begin(), used.end(), 0));
}

} // namespace

TEST_CASE("Delaunay triangles of a lattice: four points on every circle, three on every line",
          "[delaunay]") {
  // 300 x 200 given row by row, as a cloud's nodes come: inserted so, each point of a row would
  // flip the fan of long edges above the row (a quadratic count).
  for (const auto& [nx, ny] :
       {std::pair{7, 5}, std::pair{2, 2}, std::pair{40, 3}, std::pair{300, 200}}) {
    INFO(nx << " x " << ny << " points");
    std::vector<Vec2> x;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) x.emplace_back(0.5 * i, 0.25 * j);
    const std::vector<Triangle> tri = geometry::delaunay(x);
    // A triangulation of n points with h of them on the hull's boundary has 2n - h - 2 triangles.
    const int n = nx * ny, h = 2 * (nx + ny) - 4;
    CHECK(static_cast<int>(tri.size()) == 2 * n - h - 2);
    CHECK(covered_area(x, tri) == Approx(0.5 * (nx - 1) * 0.25 * (ny - 1)).epsilon(1e-12));
    CHECK(unused_points(x.size(), tri) == 0);
  }
}

TEST_CASE("Delaunay triangles of random points: no point inside a triangle's circle",
          "[delaunay]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  std::vector<Vec2> x(400);
  for (Vec2& p : x) p = Vec2(u(rng), 0.1 * u(rng));
  const std::vector<Triangle> tri = geometry::delaunay(x);
  covered_area(x, tri);
  CHECK(unused_points(x.size(), tri) == 0);
  CHECK(static_cast<int>(tri.size()) >= static_cast<int>(x.size())); // 2n - h - 2, h small
  int violations = 0;
  for (const Triangle& t : tri) {
    const Vec2 &a = x[t[0]], &b = x[t[1]], &c = x[t[2]];
    // The circumcentre from the perpendicular bisectors.
    const double d =
        2.0 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
    const Vec2 o((a.squaredNorm() * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) +
                  c.squaredNorm() * (a.y() - b.y())) /
                     d,
                 (a.squaredNorm() * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) +
                  c.squaredNorm() * (b.x() - a.x())) /
                     d);
    const double r = (a - o).norm();
    for (const Vec2& p : x) violations += (p - o).norm() < r * (1.0 - 1e-9);
  }
  CHECK(violations == 0);
}

TEST_CASE("the triangles of a cloud's nodes in its body cover the body, chords along holes",
          "[delaunay]") {
  using geometry::Domain;
  struct Case {
    const char* name;
    Domain domain;
    double spacing;
    std::vector<geometry::Refinement> boxes;
    double area;     // of the body
    double arcs = 0; // length of the holes' boundary in the body
    double radius = 1;
  };
  const auto holed = [](Domain d, Vec2 c, double r) {
    d.add_hole({c, r, "hole"});
    return d;
  };
  const double pi = std::acos(-1.0);
  const Domain cook = Domain::polygon({{0, 0}, {48, 44}, {48, 60}, {0, 44}});
  const Domain l_shape = Domain::polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  const std::vector<Case> cases = {
      {"plate, hole inside, spacing divides",
       holed(Domain::rectangle({0, 0}, {10, 6}), {4, 3}, 1.5),
       0.5,
       {},
       60 - pi * 2.25,
       2 * pi * 1.5,
       1.5},
      {"plate, hole inside, spacing does not divide",
       holed(Domain::rectangle({0, 0}, {10, 6}), {4, 3}, 1.5),
       0.37,
       {},
       60 - pi * 2.25,
       2 * pi * 1.5,
       1.5},
      {"plate, a hole of seven chords (spacing = radius)",
       holed(Domain::rectangle({0, 0}, {5, 5}), {2.5, 2.5}, 1.0),
       1.0,
       {},
       25 - pi,
       2 * pi,
       1.0},
      {"plate, two holes, one cut by its edge",
       holed(holed(Domain::rectangle({0, 0}, {10, 6}), {3, 3}, 1.5), {10, 2}, 1.0),
       0.4,
       {},
       60 - pi * 2.25 - pi / 2,
       2 * pi * 1.5 + pi,
       1.0},
      {"strip, quarter hole at a corner, refinement box",
       holed(Domain::rectangle({0, 0}, {10, 18}), {0, 0}, 5),
       1.0,
       {{BoundingBox{{3, 0}, {7, 4}}, 0.25}},
       180 - pi * 25 / 4,
       pi * 5 / 2,
       5},
      {"Cook's trapezoid", cook, 2.0, {}, 48.0 * (44 + 16) / 2},
      {"Cook's trapezoid, spacing 3.3, box",
       cook,
       3.3,
       {{BoundingBox{{30, 40}, {48, 60}}, 1.1}},
       48.0 * (44 + 16) / 2},
      {"L-shape (a re-entrant corner)", l_shape, 0.15, {}, 3.0, 0},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const geometry::NodeCloud cloud = geometry::generate_nodes(c.domain, c.spacing, c.boxes);
    const std::vector<Triangle> tri = geometry::body_triangles(c.domain, cloud.x);
    REQUIRE(!tri.empty());
    const double covered = covered_area(cloud.x, tri);
    // Chords cut into a hole: at most the sagitta h^2 / (8 R) along its boundary's length.
    const double chords = c.arcs * c.spacing * c.spacing / (8.0 * c.radius);
    CHECK(covered >= c.area * (1.0 - 1e-12));
    CHECK(covered <= c.area * (1.0 + 1e-12) + chords);
    CHECK(unused_points(cloud.x.size(), tri) == 0);
  }
}

TEST_CASE("points too sparse along a hole give no body triangles", "[delaunay]") {
  geometry::Domain d = geometry::Domain::rectangle({0, 0}, {1, 1});
  d.add_hole({{0.5, 0.5}, 0.2, "hole"});
  // The corners alone: the diagonal crosses the hole, which no point marks.
  CHECK(geometry::body_triangles(d, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}).empty());
  // Their triangles kept where the hole is marked by points on its circle.
  std::vector<Vec2> x = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 24; ++k) {
    const double a = 2.0 * std::acos(-1.0) * k / 24;
    x.push_back(Vec2(0.5, 0.5) + 0.2 * Vec2(std::cos(a), std::sin(a)));
  }
  CHECK(!geometry::body_triangles(d, x).empty());
}
