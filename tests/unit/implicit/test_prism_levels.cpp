// Refinement boxes along z in a meshfree prism (implicit/prism_levels, solid_points): a table of
// the boxes a user writes first (through the whole depth, a range inside it, one at a face, one
// of no thickness, two that overlap, one that stops a sliver short of the section's edge,
// spacings that do not divide the depth or each other), on a block and on a plate with a hole.
// For each: the volume points integrate the body's volume and first moments exactly, the cells
// of the cell-mean strain are numbered apart, every face's area is exact, the shape functions
// exist at every volume point and reproduce a linear field, and the nodes stand where the levels
// say (refined nodes on their box's layers with supports of their own spacing, the others on the
// base layers).
#include "meshfree/implicit/prism_levels.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/implicit/solid_space.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

using namespace mf;

namespace {

struct Case {
  const char* what;
  double depth, spacing, cell_size;
  std::vector<geometry::Refinement> boxes;
};

/// A box given in the plane: it refines the section through the whole depth.
geometry::Refinement box(Vec2 lo, Vec2 hi, double spacing) {
  geometry::Refinement r;
  r.box = BoundingBox{lo, hi};
  r.spacing = spacing;
  return r;
}

/// A box given in 3D: it refines along z over [z_lo, z_hi] too.
geometry::Refinement box(Vec2 lo, Vec2 hi, double spacing, double z_lo, double z_hi) {
  geometry::Refinement r = box(lo, hi, spacing);
  r.along_z = true;
  r.z_lo = z_lo;
  r.z_hi = z_hi;
  return r;
}

std::vector<Case> cases() {
  return {
      {"no box", 0.5, 0.125, 0.125, {}},
      {"a box in the plane", 0.5, 0.125, 0.125, {box({0.3, 0.2}, {0.7, 0.5}, 0.0625)}},
      {"a 3D box through the whole depth and past it",
       0.5,
       0.125,
       0.125,
       {box({0.3, 0.2}, {0.7, 0.5}, 0.0625, -1.0, 1.0)}},
      {"a range inside the depth, off the base levels",
       0.5,
       0.125,
       0.0875,
       {box({0.3, 0.2}, {0.7, 0.5}, 0.0625, 0.1, 0.3)}},
      {"a range at the front face",
       0.5,
       0.125,
       0.125,
       {box({0.2, 0.2}, {0.6, 0.5}, 0.05, 0.3, 2.0)}},
      {"a range of no thickness",
       0.5,
       0.125,
       0.125,
       {box({0.2, 0.2}, {0.6, 0.5}, 0.0625, 0.2, 0.2)}},
      {"a 3D box and a plane one that overlap, spacings that divide nothing",
       0.55,
       0.125,
       0.125,
       {box({0.0, 0.0}, {1.0, 0.75}, 0.04, 0.2, 0.26), box({0.45, 0.25}, {0.75, 0.5}, 0.07)}},
      {"a box in the plane that stops a sliver short of the section's edge",
       0.5,
       0.125,
       0.125,
       {box({0.0, 0.0}, {1.0, 0.61}, 0.05)}},
      {"a 3D box that stops a sliver short of the section's edge",
       0.5,
       0.125,
       0.125,
       {box({0.0, 0.0}, {0.86, 0.61}, 0.05, 0.1, 0.3)}},
      {"two 3D boxes, one inside the other",
       0.5,
       0.125,
       0.125,
       {box({0.2, 0.1}, {0.8, 0.5}, 0.0625, 0.0, 0.3),
        box({0.4, 0.2}, {0.6, 0.4}, 0.03, 0.1, 0.2)}},
  };
}

geometry::Prism block(double depth) {
  return {geometry::Domain::rectangle({0.0, 0.0}, {1.0, 0.75}), 0.0, depth, {}};
}

geometry::Prism holed(double depth) {
  geometry::Domain plate = geometry::Domain::rectangle({0.0, 0.0}, {1.0, 0.75});
  plate.add_hole({Vec2(0.55, 0.35), 0.15, "hole"});
  return {plate, 0.0, depth, {}};
}

spec::DiscretisationSpec discretisation(const Case& c) {
  spec::DiscretisationSpec d;
  d.spacing = c.spacing;
  d.cell_size = c.cell_size;
  d.order = 2;
  d.boundary_order = 2;
  d.cut_arcs = true;
  d.refinement = c.boxes;
  d.shape.dim = 3;
  return d;
}

/// The largest error of the shape functions' reproduction of 1, x, y and z at the points.
double reproduction_error(const implicit::SolidNodes& nodes, const spec::DiscretisationSpec& d,
                          const std::vector<Vec3>& x) {
  const implicit::SolidSpace space(nodes, d.shape, d.dilation.maxCoeff());
  std::vector<int> rows(x.size());
  std::iota(rows.begin(), rows.end(), 0);
  const implicit::SolidShapeTable t = space.shape_table(x, rows, space.support_lists(x), false);
  double worst = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    double one = 0.0;
    Vec3 at = Vec3::Zero();
    for (int e = t.offset[k]; e < t.offset[k + 1]; ++e) {
      one += t.phi[e];
      at += t.phi[e] * nodes.x[t.node[e]];
    }
    worst = std::max({worst, std::abs(one - 1.0), (at - x[k]).lpNorm<Eigen::Infinity>()});
  }
  return worst;
}

} // namespace

TEST_CASE("prism levels: each box's cells integrate the body and its faces exactly",
          "[solid3d][levels]") {
  for (const Case& c : cases())
    for (const bool hole : {false, true}) {
      CAPTURE(c.what, hole);
      const geometry::Prism body = hole ? holed(c.depth) : block(c.depth);
      spec::DiscretisationSpec d = discretisation(c);
      // The cells a hole cuts are mapped onto their curved part, which a Gauss rule integrates
      // within 2e-9 at order 5 (not exactly): the tolerance of the holed plate.
      if (hole) d.order = d.boundary_order = 5;
      const double tol = hole ? 1e-8 : 1e-12;
      const double area = hole ? 0.75 - M_PI * 0.0225 : 0.75;
      const implicit::SolidPoints v = implicit::prism_volume_points(body, d);
      double volume = 0.0, mz = 0.0;
      for (std::size_t k = 0; k < v.x.size(); ++k) {
        volume += v.weight[k];
        mz += v.weight[k] * v.x[k].z();
      }
      CHECK(volume == Approx(area * c.depth).epsilon(tol));
      CHECK(mz == Approx(area * c.depth * c.depth / 2.0).epsilon(tol));
      // The cells of the cell-mean strain: each slab's pieces apart from every other slab's.
      std::map<int, std::pair<double, double>> reach;
      for (std::size_t k = 0; k < v.x.size(); ++k) {
        const auto it = reach.emplace(v.cell[k], std::make_pair(v.x[k].z(), v.x[k].z())).first;
        it->second.first = std::min(it->second.first, v.x[k].z());
        it->second.second = std::max(it->second.second, v.x[k].z());
      }
      for (const auto& [cell, z] : reach) REQUIRE(z.second - z.first < c.spacing);
      double sides = 0.0, ends = 0.0;
      for (double w : implicit::prism_face_points(body, d, body.names_selected("x_max")).weight)
        sides += w;
      for (double w : implicit::prism_face_points(body, d, {"front"}).weight) ends += w;
      CHECK(sides == Approx(0.75 * c.depth).epsilon(1e-12));
      CHECK(ends == Approx(area).epsilon(tol));
    }
}

TEST_CASE("prism levels: the shape functions reproduce a linear field at every volume point",
          "[solid3d][levels]") {
  for (const Case& c : cases())
    for (const bool hole : {false, true}) {
      CAPTURE(c.what, hole);
      const geometry::Prism body = hole ? holed(c.depth) : block(c.depth);
      const spec::DiscretisationSpec d = discretisation(c);
      const implicit::SolidNodes n = implicit::prism_nodes(body, d);
      CHECK(reproduction_error(n, d, implicit::prism_volume_points(body, d).x) < 1e-10);
    }
}

TEST_CASE("prism levels: refined nodes stand on their box's layers, the others on the base's",
          "[solid3d][levels]") {
  // Base layers of 0.125 over a depth of 0.5; the box's range [0.1, 0.3] widens to the base
  // levels 0 and 0.375 and takes 6 layers of 0.0625 there. At z = 0.375, an end of the range
  // inside the body, the coarse cloud stands.
  const Case c = cases()[3];
  const implicit::SolidNodes n = implicit::prism_nodes(block(c.depth), discretisation(c));
  std::set<long> fine_z, coarse_z;
  for (std::size_t i = 0; i < n.x.size(); ++i) {
    const long z = std::lround(n.x[i].z() / 0.0625);
    REQUIRE(std::abs(n.x[i].z() - 0.0625 * z) < 1e-14);
    if (n.spacing[i] < 0.1) {
      CHECK(n.spacing[i] == Approx(0.0625).epsilon(1e-14)); // a support of its own layers
      CHECK(c.boxes[0].box.contains(n.x[i].head<2>(), 1e-12));
      fine_z.insert(z);
    } else {
      CHECK(n.spacing[i] == Approx(0.125).epsilon(1e-14));
      coarse_z.insert(z);
    }
  }
  CHECK(fine_z == std::set<long>{0, 1, 2, 3, 4, 5});
  CHECK(coarse_z == std::set<long>{0, 2, 4, 6, 8});
  CHECK(implicit::node_levels(block(c.depth), discretisation(c)).size() == 8);
}

TEST_CASE("prism levels: a box given in the plane refines the section on the base layers",
          "[solid3d][levels]") {
  const Case c = cases()[1];
  const implicit::SolidNodes n = implicit::prism_nodes(block(c.depth), discretisation(c));
  for (std::size_t i = 0; i < n.x.size(); ++i) {
    const long z = std::lround(n.x[i].z() / 0.125);
    REQUIRE(std::abs(n.x[i].z() - 0.125 * z) < 1e-14);
    CHECK(n.spacing[i] == Approx(0.125).epsilon(1e-14)); // supports reach the next base layer
  }
  // The refined plane cloud on each of the 5 base levels.
  const geometry::NodeCloud plane =
      geometry::generate_nodes(block(c.depth).section, c.spacing, c.boxes);
  CHECK(n.x.size() == 5 * plane.x.size());
  CHECK(implicit::node_levels(block(c.depth), discretisation(c)).size() == 5);
}

TEST_CASE("prism levels: a 3D box at a spherical cavity", "[solid3d][levels][sphere]") {
  // The octant cavity (a ball of radius 1 at a corner of a cube of 2.5), a box of 0.125 given in
  // 3D around the cavity's reach: the volume within the cut cells' error (2 levels: 2.6e-7 on
  // the plain cloud), nodes on the sphere, and linear reproduction at every volume point.
  const geometry::Prism body{geometry::Domain::rectangle({0.0, 0.0}, {2.5, 2.5}),
                             0.0,
                             2.5,
                             {geometry::Sphere{Vec3::Zero(), 1.0, "cavity"}}};
  Case c{"a 3D box at the cavity", 2.5, 0.25, 0.25, {box({0.0, 0.0}, {1.5, 1.5}, 0.125, 0.0, 1.5)}};
  spec::DiscretisationSpec d = discretisation(c);
  d.cut_levels = 2;
  const implicit::SolidPoints v = implicit::prism_volume_points(body, d);
  double volume = 0.0;
  for (double w : v.weight) volume += w;
  CHECK(volume == Approx(2.5 * 2.5 * 2.5 - M_PI / 6.0).epsilon(1e-5));
  const implicit::SolidNodes n = implicit::prism_nodes(body, d);
  for (const Vec3& x : n.x) REQUIRE(body.spheres[0].distance(x) > -1e-12);
  CHECK(reproduction_error(n, d, v.x) < 1e-10);
}
