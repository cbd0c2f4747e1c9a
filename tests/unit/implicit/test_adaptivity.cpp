// Error-driven refinement: Doerfler's marking, the recovery estimate against exact solutions
// (zero on a linear field, the exact energy error's size and rate on Kirsch's plate), clouds
// graded where boxes leave one coarser column between them, and adapted clouds against uniform
// ones at the same cost.
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>

using namespace mf;

TEST_CASE("Doerfler marking: the fewest largest values that reach the fraction, ties together",
          "[adaptivity]") {
  using implicit::doerfler_marking;
  CHECK(doerfler_marking({1, 4, 9, 16}, 0.5) == std::vector<int>{3});    // 16 >= 15
  CHECK(doerfler_marking({1, 4, 9, 16}, 0.6) == std::vector<int>{2, 3}); // 25 >= 18
  CHECK(doerfler_marking({1, 4, 9, 16}, 1.0) == std::vector<int>{0, 1, 2, 3});
  CHECK(doerfler_marking({5, 1, 5 * (1 + 1e-12)}, 0.3) == std::vector<int>{0, 2}); // mirror pair
  CHECK(doerfler_marking({0, 0, 0}, 0.5).empty());
}

TEST_CASE("recovery estimate: zero where the solution is linear, on a uniform and a graded "
          "cloud",
          "[adaptivity]") {
  // VCI reproduces the linear field (test_elasticity) up to the penalty's own error (about
  // 1.6e-7 at alpha = 1e10), so sigma_h is constant and so is its recovery. The second cloud's
  // boxes leave one coarser column between them, which the graded supports of adapted clouds
  // cover.
  for (const std::string& boxes :
       {std::string("[]"), std::string("[{box: [[0.3, 0.3], [0.6, 0.5]], spacing: 0.05}, "
                                       "{box: [[0.7, 0.3], [0.9, 0.5]], spacing: 0.05}]")}) {
    const auto r = implicit::solve_elastic_static(
        load_problem("patch_test",
                     {"discretisation.quadrature.correction=vci",
                      "discretisation.quadrature.order=2", "boundary.0.penalty=1e10",
                      "discretisation.refinement=" + boxes, "discretisation.adapt.target=0.5"}),
        test_session());
    INFO("boxes " << boxes);
    CHECK(r.error_energy < 3e-7);
    CHECK(r.estimate.relative() < 3e-7);
    CHECK(r.estimate.energy2 > 0.0);
  }
}

namespace {

struct Run {
  int dofs = 0;
  double exact = 0.0, estimate = 0.0;
};

/// Kirsch's plate at `spacing` with the `extra` settings, adapted to `target`.
Run kirsch(double spacing, const std::string& target, std::vector<std::string> extra = {}) {
  extra.push_back("discretisation.spacing=" + std::to_string(spacing));
  extra.push_back("discretisation.adapt.target=" + target);
  extra.push_back("discretisation.adapt.passes=8");
  const auto& session = test_session();
  const implicit::AdaptedProblem p = implicit::adapted_problem(
      load_problem("plate_hole_kirsch", extra), [&](const spec::ProblemSpec& s) {
        return implicit::solve_elastic_static(s, session).estimate;
      });
  const auto r = implicit::solve_elastic_static(p.spec, session);
  std::cout << "Kirsch from h = " << spacing << ", target " << target << ": " << r.dofs
            << " DOFs, exact energy error " << r.error_energy << ", estimate "
            << r.estimate.relative() << "\n";
  return {r.dofs, r.error_energy, r.estimate.relative()};
}

} // namespace

TEST_CASE("recovery estimate on Kirsch's plate: the exact energy error's size and rate",
          "[adaptivity]") {
  // A target of 0.5 is met at once: the uniform clouds as they are, with their estimates.
  const std::vector<double> h{0.25, 0.125};
  std::vector<Run> runs;
  for (double s : h) runs.push_back(kirsch(s, "0.5"));
  // Measured: estimate / exact 1.41 and 1.46; rates 1.32 and 1.37.
  for (const Run& r : runs) {
    CHECK(r.estimate / r.exact > 1.0);
    CHECK(r.estimate / r.exact < 2.0);
  }
  const double rate_exact = std::log(runs[0].exact / runs[1].exact) / std::log(h[0] / h[1]);
  const double rate_estimate =
      std::log(runs[0].estimate / runs[1].estimate) / std::log(h[0] / h[1]);
  CHECK(rate_exact > 0.9);
  CHECK(std::abs(rate_estimate - rate_exact) < 0.2);
}

TEST_CASE("adapted Kirsch plate: below the uniform cloud's exact error with fewer DOFs, with "
          "the linear basis, VCI and the quadratic basis",
          "[adaptivity]") {
  // Measured, from h = 0.5 to the target 0.015, against the uniform h = 0.125 (3,262 DOFs):
  //   linear     1,184 DOFs, exact energy error 0.0088 (uniform 0.0096), estimate 1.3 times
  //   VCI on 2 x 2 points   974 DOFs, 0.0063 (uniform 0.0094), estimate 2.0 times
  //   quadratic  1,376 DOFs, 0.0024 (uniform 0.0062), estimate 3.5 times
  // The recovery (nodal averages through the shape functions) is no more accurate than the
  // quadratic basis's own stress, so its estimate measures the recovery's error as much as the
  // solution's and lies further above the exact error, the more so the better the solution.
  struct Variant {
    std::string name;
    std::vector<std::string> settings;
    double dofs_share;  // of the uniform cloud's DOFs, at most
    double effectivity; // estimate / exact error, at most
  };
  const std::vector<Variant> variants{
      {"linear", {}, 0.5, 3.0},
      {"vci",
       {"discretisation.quadrature.correction=vci", "discretisation.quadrature.order=2"},
       0.5,
       3.0},
      {"quadratic", {"discretisation.basis=quadratic", "discretisation.dilation=3"}, 0.7, 4.0}};
  for (const Variant& v : variants) {
    INFO(v.name);
    const Run uniform = kirsch(0.125, "0.5", v.settings);
    const Run adapted = kirsch(0.5, "0.015", v.settings);
    CHECK(adapted.estimate <= 0.015);
    CHECK(adapted.exact < uniform.exact);
    CHECK(adapted.dofs < v.dofs_share * uniform.dofs);
    CHECK(adapted.estimate / adapted.exact > 1.0);
    CHECK(adapted.estimate / adapted.exact < v.effectivity);
  }
}

TEST_CASE("graded supports: a column left between two boxes no longer leaves points whose "
          "shape functions are undefined",
          "[adaptivity]") {
  // Within a box of spacing 1 (base spacing 2), boxes of spacing 0.5 around x = 5 and x = 11
  // leave the column x = 8 of spacing 1 between borders at 7 and 9 whose nodes are the finer
  // boxes' (as adapted clouds' nested boxes make them): the points of that column are covered
  // by it alone and the borders' nodes (supports of radius 1), which reach it only on their rims.
  const geometry::Domain body = geometry::Domain::rectangle({0, 0}, {16, 8});
  const std::vector<geometry::Refinement> boxes{{BoundingBox{{0, 0}, {16, 8}}, 1.0},
                                                {BoundingBox{{3, 2}, {7, 6}}, 0.5},
                                                {BoundingBox{{9, 2}, {13, 6}}, 0.5}};
  kernels::ShapeSettings shape;
  shape.dim = 2;
  const std::vector<Vec2> points{{8, 4}, {8, 3.5}, {7.9, 4.2}};
  std::vector<int> rows{0, 1, 2};
  geometry::NodeCloud plain = geometry::generate_nodes(body, 2.0, boxes);
  geometry::NodeCloud graded = plain;
  geometry::grade_spacing(graded);
  const implicit::MeshfreeSpace bare(plain, shape, Vec2(2, 2));
  CHECK_THROWS_WITH(bare.shape_table(points, rows, bare.support_lists(points), true),
                    Catch::Contains("shape functions are undefined"));
  const implicit::MeshfreeSpace space(graded, shape, Vec2(2, 2));
  const implicit::ShapeTable t = space.shape_table(points, rows, space.support_lists(points), true);
  for (int r = 0; r < t.rows(); ++r) {
    double sum = 0.0;
    Vec2 first = Vec2::Zero();
    for (int q = t.offset[r]; q < t.offset[r + 1]; ++q) {
      sum += t.phi[q];
      first += t.phi[q] * graded.x[t.node[q]];
    }
    CHECK(sum == Approx(1.0).margin(1e-12));
    CHECK((first - points[r]).norm() < 1e-11);
  }
}

TEST_CASE("the refinement stops where the user bounds it: a pass count or a node count, and a spacing "
          "that does not divide the body refines as one that does",
          "[adaptivity]") {
  const auto& session = test_session();
  const auto adapt = [&](const std::vector<std::string>& o) {
    return implicit::adapt_nodes(load_problem("plate_hole_kirsch", o),
                                 [&](const spec::ProblemSpec& s) {
                                   return implicit::solve_elastic_static(s, session).estimate;
                                 });
  };
  const std::string from = "discretisation.spacing=0.5",
                    target = "discretisation.adapt.target=0.015";
  SECTION("one pass: the cloud as it is") {
    const implicit::Adaptation a = adapt({from, target, "discretisation.adapt.passes=1"});
    CHECK(a.ended == "passes used");
    CHECK(a.passes.size() == 1);
    CHECK(a.refinement.empty());
    CHECK(a.nodes == a.passes.front().nodes);
  }
  SECTION("max_nodes: the last refinement within it is kept") {
    const implicit::Adaptation a = adapt({from, target, "discretisation.adapt.max_nodes=400"});
    CHECK(a.ended == "max_nodes reached");
    CHECK(a.nodes <= 400);
    CHECK(a.passes.back().estimate > 0.015);
    CHECK(a.passes.back().marked == 0);
  }
  SECTION("h = 0.45 (5 / 0.45 = 11.1 intervals): the target reached") {
    const implicit::Adaptation a =
        adapt({"discretisation.spacing=0.45", target, "discretisation.adapt.passes=8"});
    CHECK(a.ended == "target reached");
    CHECK(a.passes.back().estimate <= 0.015);
    CHECK(a.nodes < 1000);
  }
}
