// Pairs within the sum of per-point radii (the SPH neighbour search) against an all-pairs check.
#include "meshfree/neighbors/reach_pairs.hpp"
#include <catch2/catch.hpp>
#include <omp.h>
#include <random>

using namespace mf;

namespace {
/// Every pair by the definition: j != i with r2 < ((r_i + r_j) scale)^2, rows ascending.
neighbors::PairList all_pairs(const std::vector<double>& x, const std::vector<double>& radius,
                              double scale, int rows) {
  neighbors::PairList out;
  const int n = static_cast<int>(radius.size());
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < n; ++j) {
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double dx = x[3 * i + d] - x[3 * j + d];
        r2 += dx * dx;
      }
      const double reach = (radius[i] + radius[j]) * scale;
      if (j != i && r2 < reach * reach) out.partner.push_back(j);
    }
    out.offset.push_back(static_cast<long>(out.partner.size()));
  }
  return out;
}

/// n points in [0, 1]^dim; radii drawn between r0 and ratio r0, smaller on the left half (a
/// dense region beside a sparse one, as in a shock tube).
void cloud(int n, int dim, double r0, double ratio, unsigned seed, std::vector<double>& x,
           std::vector<double>& radius) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  x.assign(3 * static_cast<std::size_t>(n), 0.0);
  radius.resize(n);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) x[3 * i + d] = u(gen);
    const double f = x[3 * i] < 0.5 ? u(gen) * 0.2 : 0.8 + 0.2 * u(gen);
    radius[i] = r0 * std::pow(ratio, f);
  }
}
} // namespace

TEST_CASE("pairs within per-point reach match the all-pairs definition", "[neighbors]") {
  for (int dim = 1; dim <= 3; ++dim) {
    const int n = dim == 1 ? 400 : dim == 2 ? 1500 : 2000;
    const double r0 = dim == 1 ? 0.002 : dim == 2 ? 0.01 : 0.03;
    for (const double ratio : {1.0, 8.0}) {
      std::vector<double> x, radius;
      cloud(n, dim, r0, ratio, 7u + dim, x, radius);
      // The last 10% play ghosts: partners without rows of their own.
      const int rows = n - n / 10;
      const neighbors::PairList want = all_pairs(x, radius, 1.5, rows);
      const neighbors::PairList got = neighbors::pairs_within_reach(x, radius, 1.5, rows);
      INFO("dim " << dim << ", ratio " << ratio);
      REQUIRE(got.rows() == rows);
      CHECK(got.offset == want.offset);
      CHECK(got.partner == want.partner);
      CHECK(want.partner.size() > 2u * static_cast<std::size_t>(rows));
    }
  }
}

TEST_CASE("pairs within reach: coincident points, one class, any thread count", "[neighbors]") {
  // Two points at one place are partners (r2 = 0 < reach^2); a point far away has none.
  const std::vector<double> x = {0, 0, 0, 0, 0, 0, 10, 0, 0};
  const std::vector<double> radius = {1.0, 1.0, 1.0};
  const neighbors::PairList p = neighbors::pairs_within_reach(x, radius, 1.0, 3);
  CHECK(p.offset == std::vector<long>{0, 1, 2, 2});
  CHECK(p.partner == std::vector<int>{1, 0});
  // A point exactly at the reach is not a partner (strict <).
  const std::vector<double> y = {0, 0, 0, 2, 0, 0};
  CHECK(neighbors::pairs_within_reach(y, {1.0, 1.0}, 1.0, 2).partner.empty());

  std::vector<double> c, r;
  cloud(3000, 2, 0.005, 8.0, 3u, c, r);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const neighbors::PairList one = neighbors::pairs_within_reach(c, r, 1.2, 3000);
  omp_set_num_threads(2);
  const neighbors::PairList two = neighbors::pairs_within_reach(c, r, 1.2, 3000);
  omp_set_num_threads(threads);
  CHECK(one.partner == two.partner);
  CHECK(one.offset == two.offset);
}
