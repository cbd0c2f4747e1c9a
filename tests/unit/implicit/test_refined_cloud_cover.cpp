// Refined node clouds cover their body: wherever a refinement box stops near the body's edge
// (a spacing that divides the body or not, a box on any side, at a corner, round a hole, nested
// boxes), the shape functions of the plain cloud (linear basis, dilation 2) are defined at every
// point of the body and reproduce a linear field, and no two nodes stand a sliver apart.
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include "shape_reproduction.hpp"
#include <catch2/catch.hpp>
#include <sstream>

using namespace mf;

namespace {

struct Case {
  const char* what;
  Vec2 size;      // the rectangle [0, size]
  double hole;    // radius of a hole centred at the origin (0 for none)
  double spacing; // base spacing
  std::vector<geometry::Refinement> boxes;
};

geometry::Refinement box(Vec2 lo, Vec2 hi, double h) {
  return {BoundingBox{lo, hi}, h};
}

/// Points of an n x n grid strictly inside the rectangle that lie in the body.
std::vector<Vec2> body_points(const geometry::Domain& body, const Vec2& size, int n) {
  std::vector<Vec2> p;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 q((i + 0.5) / n * size.x(), (j + 0.5) / n * size.y());
      if (body.contains(q)) p.push_back(q);
    }
  return p;
}

/// The smallest distance between two nodes over the finest of their spacings and of the local
/// spacings where they stand.
double smallest_gap(const geometry::NodeCloud& cloud, const Case& c) {
  const neighbors::PointGrid grid(cloud.x, c.spacing);
  const auto local = [&](const Vec2& p) { return geometry::local_spacing(p, c.spacing, c.boxes); };
  double gap = 1e300;
  for (std::size_t i = 0; i < cloud.x.size(); ++i)
    grid.for_each_within(cloud.x[i], c.spacing, [&](int j) {
      if (j == static_cast<int>(i)) return;
      const double h =
          std::min({local(cloud.x[i]), local(cloud.x[j]), cloud.spacing[i], cloud.spacing[j]});
      gap = std::min(gap, (cloud.x[i] - cloud.x[j]).norm() / h);
    });
  return gap;
}

} // namespace

TEST_CASE("a refinement box that stops near the body's edge leaves no strip the boundary's own "
          "row alone covers",
          "[geometry][refinement]") {
  std::vector<Case> cases;
  // A box ending a little short of the top edge, at its edge, at every offset the two lattices
  // can have against each other (the base row y = 0.625 lies within half a fine spacing).
  for (double top : {0.55, 0.575, 0.6, 0.61, 0.62, 0.625, 0.64, 0.65, 0.7, 0.75})
    cases.push_back({"top", {1, 0.75}, 0, 0.125, {box({0, 0}, {1, top}, 0.05)}});
  for (double bottom : {0.05, 0.1, 0.125, 0.14, 0.15, 0.2})
    cases.push_back({"bottom", {1, 0.75}, 0, 0.125, {box({0, bottom}, {1, 0.75}, 0.05)}});
  for (double right : {0.85, 0.86, 0.875, 0.9})
    cases.push_back({"right", {1, 0.75}, 0, 0.125, {box({0, 0}, {right, 0.75}, 0.05)}});
  for (double corner : {0.6, 0.61, 0.62})
    cases.push_back({"corner", {1, 0.75}, 0, 0.125, {box({0, 0}, {corner + 0.25, corner}, 0.05)}});
  // Spacings that do not divide the body: fitted base steps beside a box's lattice.
  for (double top : {0.6, 0.62, 0.65})
    cases.push_back({"fitted", {1.03, 0.77}, 0, 0.125, {box({0, 0}, {1.03, top}, 0.04)}});
  for (double h : {0.03, 0.04, 0.06})
    cases.push_back({"fine spacing", {1, 0.75}, 0, 0.125, {box({0, 0}, {1, 0.61}, h)}});
  // Nested boxes, the inner one stopping short of the outer one's edge and the body's.
  cases.push_back({"nested",
                   {1, 0.75},
                   0,
                   0.25,
                   {box({0, 0}, {1, 0.61}, 0.125), box({0, 0}, {1, 0.58}, 0.05)}});
  // A box round a hole that stops short of the plate's outer edges.
  for (double reach : {2.4, 2.45, 2.5})
    cases.push_back({"hole", {3, 3}, 1.0, 0.5, {box({0, 0}, {reach, reach}, 0.2)}});

  kernels::ShapeSettings shape;
  shape.dim = 2;
  for (const Case& c : cases) {
    geometry::Domain body = geometry::Domain::rectangle({0, 0}, c.size);
    if (c.hole > 0.0) body.add_hole({{0, 0}, c.hole, "hole"});
    const geometry::NodeCloud cloud = geometry::generate_nodes(body, c.spacing, c.boxes);
    std::ostringstream name;
    name << c.what << ": box " << c.boxes.back().box.lo.transpose() << " .. "
         << c.boxes.back().box.hi.transpose() << " at " << c.boxes.back().spacing;
    INFO(name.str());
    CHECK(smallest_gap(cloud, c) > 0.44);
    const implicit::MeshfreeSpace space(cloud, shape, Vec2(2, 2));
    const std::vector<Vec2> points = body_points(body, c.size, 97);
    try {
      CHECK(linear_reproduction_error(space, points) < 1e-10);
    } catch (const std::exception& e) {
      FAIL_CHECK(e.what());
    }
  }
}
