// Integration points grouped for threaded assembly: every point once, no node shared within a
// colour, and sums that do not depend on the number of threads.
#include "meshfree/implicit/point_groups.hpp"
#include <catch2/catch.hpp>
#include <omp.h>
#include <random>
#include <set>

using namespace mf;
using implicit::PointGroups;
using implicit::ShapeTable;

namespace {

/// Nodes on a lattice of spacing h over [0, 4] x [0, 2] (with a finer patch), points scattered
/// at random, each point's support the nodes within 2 h.
struct Cloud {
  std::vector<Vec2> nodes, points;
  ShapeTable table;
};

Cloud cloud() {
  Cloud c;
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 40; ++i) c.nodes.emplace_back(0.1 * i, 0.1 * j);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) c.nodes.emplace_back(1.0 + 0.025 * i, 0.5 + 0.025 * j);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 4.0), uy(0.0, 2.0);
  for (int k = 0; k < 3000; ++k) {
    const Vec2 p(ux(rng), uy(rng));
    c.points.push_back(p);
    for (int I = 0; I < static_cast<int>(c.nodes.size()); ++I)
      if ((c.nodes[I] - p).norm() <= 0.2) {
        c.table.node.push_back(I);
        c.table.phi.push_back(1.0 / (1.0 + I + k));
      }
    c.table.offset.push_back(static_cast<int>(c.table.node.size()));
  }
  return c;
}

} // namespace

TEST_CASE("point groups: every point once, and no node shared by two points of one pass",
          "[assembly]") {
  const Cloud c = cloud();
  const PointGroups g(c.table, c.points, c.nodes);
  REQUIRE(g.tiles() > 8);
  REQUIRE(g.independent(c.table, static_cast<int>(c.nodes.size())));
  std::vector<int> visits(c.table.rows(), 0);
  g.for_each([&](int r, int) {
#pragma omp atomic
    ++visits[r];
  });
  for (int v : visits) REQUIRE(v == 1);
}

TEST_CASE("point groups: sums over the points are the same on 1 and 2 threads, bit for bit",
          "[assembly]") {
  const Cloud c = cloud();
  const PointGroups g(c.table, c.points, c.nodes);
  const auto sums = [&](int threads) {
    std::vector<double> s(c.nodes.size(), 0.0);
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    g.for_each([&](int r, int) {
      for (int k = c.table.offset[r]; k < c.table.offset[r + 1]; ++k)
        s[c.table.node[k]] += c.table.phi[k] * 0.1; // unsynchronised: safe only without sharing
    });
    omp_set_num_threads(before);
    return s;
  };
  const std::vector<double> one = sums(1), two = sums(2);
  REQUIRE(one == two);
  double total = 0.0;
  for (double v : one) total += v;
  double expected = 0.0;
  for (double v : c.table.phi) expected += 0.1 * v;
  REQUIRE(total == Approx(expected).epsilon(1e-12));
}
