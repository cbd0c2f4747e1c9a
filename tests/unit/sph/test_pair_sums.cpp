// The two ways SPH sums its pairs give the same rates: each pair once with its terms sent to
// both ends (Newton's third law, the default) and every particle's whole row in global-id order
// (settings.deterministic). Every pair term is exercised: two materials, one without strength,
// the kernel-gradient correction, the artificial stress, the inter-material penalty, a symmetry
// plane's mirror images, a fixed particle, gravity and damping, on 1, 2 and 3 threads. The
// live-pair selection, packed for AVX2, keeps what the scalar one keeps, bit for bit.
#include "meshfree/core/simd_target.hpp"
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/live_pairs.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
#include "sph_test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <omp.h>
#include <vector>

using namespace mf;

namespace {

/// A jittered block of dim dimensions, n particles a side at spacing dx, the half x > 0 a solid
/// with strength and the rest a gas, with random velocities and deviatoric stresses; symmetry
/// plane x = -(half the block) mirrors the gas' left face.
sph::Hydro mixed_block(int dim, int n) {
  sph::Hydro s;
  s.dim = dim;
  const sph::Material solid = test_solid();
  sph::Material gas;
  gas.name = "gas";
  gas.eos = materials::IdealGas{};
  s.materials = {solid, gas};
  s.settings.gradient_correction = true;
  s.settings.artificial_stress = 0.3;
  s.settings.penalty.pressure = 1e8;
  s.body.gravity[dim - 1] = -9.81;
  s.body.damping = 50.0;
  s.symmetry = {{0, -0.5 * n * 1e-3}};
  const double dx = 1e-3;
  unsigned seed = 2024u;
  const auto random = [&]() { // in [-0.5, 0.5)
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / 16777216.0 - 0.5;
  };
  const int nz = dim == 3 ? n : 1, ny = dim >= 2 ? n : 1;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < ny; ++b)
      for (int a = 0; a < n; ++a) {
        double x[3] = {(a + 0.5 - 0.5 * n) * dx, 0.0, 0.0};
        if (dim >= 2) x[1] = (b + 0.5) * dx;
        if (dim == 3) x[2] = (c + 0.5) * dx;
        for (int d = 0; d < dim; ++d) x[d] += 0.1 * dx * random();
        const bool solid_side = x[0] > 0.0;
        const double rho = solid_side ? 2700.0 : 1.2;
        const int i = add(s, x, std::pow(dx, dim), rho, solid_side ? 0.0 : 2e5, 1.3 * dx,
                          solid_side ? 0 : 1, a == n - 1 && b == 0 && c == 0);
        for (int d = 0; d < dim; ++d) s.particles.v[3 * i + d] = 50.0 * random();
      }
  sph::update_state(s);
  for (int i = 0; i < s.particles.size(); ++i) {
    if (s.particles.material[i] != 0) continue;
    double* S = &s.fields.S[6 * i];
    S[0] = 2e7 * random(), S[1] = dim >= 2 ? 2e7 * random() : -0.5 * S[0];
    S[2] = -S[0] - S[1];
    if (dim >= 2) S[5] = 1e7 * random();
    if (dim == 3) S[3] = 1e7 * random(), S[4] = 1e7 * random();
    s.fields.rho[i] *= 1.0 + 0.01 * random();
  }
  sph::update_state(s);
  return s;
}

/// The largest difference between two rate arrays relative to the largest magnitude in a.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b,
                           std::size_t count) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(a[k]));
  }
  return diff / scale;
}

} // namespace

TEST_CASE("SPH: each pair once (Newton's third law) gives the rates of the whole rows",
          "[sph][rates]") {
  for (const int dim : {1, 2, 3}) {
    sph::Hydro s = mixed_block(dim, dim == 1 ? 40 : dim == 2 ? 16 : 8);
    s.settings.deterministic = true;
    sph::refresh_neighbours(s);
    sph::Rates rows;
    sph::compute_rates(s, rows);
    const std::size_t n = static_cast<std::size_t>(s.particles.owned_count());
    REQUIRE(static_cast<int>(n) < s.particles.size()); // mirror images are in the lists
    s.settings.deterministic = false;
    s.neighbours.x_at_build.clear(); // the half list is made at the next build
    sph::refresh_neighbours(s);
    REQUIRE(2 * s.neighbours.half_pairs.partner.size() > s.neighbours.pairs.partner.size());
    REQUIRE(s.neighbours.half_pairs.partner.size() < s.neighbours.pairs.partner.size());
    const int threads = omp_get_max_threads();
    for (const int t : {1, 2, 3}) {
      omp_set_num_threads(t);
      sph::Rates once;
      sph::compute_rates(s, once);
      const double dv = relative_difference(rows.dv, once.dv, 3 * n);
      const double drho = relative_difference(rows.drho, once.drho, n);
      const double de = relative_difference(rows.de, once.de, n);
      const double dS = relative_difference(rows.dS, once.dS, 6 * n);
      const double L = relative_difference(rows.grad_v, once.grad_v, 9 * n);
      std::printf("  %dD, %d thread(s), %zu particles: each pair once against whole rows: dv %.1e, "
                  "drho %.1e, de %.1e, dS %.1e, grad v %.1e\n",
                  dim, t, n, dv, drho, de, dS, L);
      CHECK(dv < 1e-13);
      CHECK(drho < 1e-13);
      CHECK(de < 1e-13);
      CHECK(dS < 1e-13);
      CHECK(L < 1e-13);
      // The fixed particle does not move.
      const std::size_t fixed = static_cast<std::size_t>(
          std::find(s.fields.fixed.begin(), s.fields.fixed.end(), 1) - s.fields.fixed.begin());
      REQUIRE(fixed < n);
      for (int d = 0; d < 3; ++d) CHECK(once.dv[3 * fixed + d] == 0.0);
    }
    omp_set_num_threads(threads);
  }
}

TEST_CASE("SPH: the live-pair selection keeps the same pairs with the same values on every "
          "instruction set, and the rates are equal bit for bit",
          "[sph][rates][simd]") {
  const std::vector<SimdTarget> targets = simd_targets();
  REQUIRE(targets.front() == SimdTarget::Baseline);
  // A row of every length from 0 to 11 (the packed selection takes four pairs at a time), with
  // a partner at the row's own place (r = 0, left out) and in 1D one exactly at 2 h_ij (left out):
  // particle 0 at the origin with h = 0.5, partners along x at 0, 1 (= 2 h_ij) and inside.
  const double along[] = {0.3, 0.0, 1.0, -0.7, 0.999, 1.5, 0.1, -1.0, 0.25, 2.0, -0.5};
  std::cout << "live pairs compared on:";
  for (SimdTarget t : targets) std::cout << ' ' << simd_target_name(t);
  std::cout << '\n';
  for (int length = 0; length <= 11; ++length) {
    neighbors::PairList list;
    for (int k = 1; k <= length; ++k) list.partner.push_back(k);
    list.offset = {0, static_cast<long>(length)};
    for (const int dim : {1, 2, 3})
      for (const kernels::SphKernel kernel :
           {kernels::SphKernel::CubicSpline, kernels::SphKernel::WendlandC2}) {
        // Coordinates beyond the model's dimension are zero, as for every particle of a body.
        std::vector<double> xh{0.0, 0.0, 0.0, 0.5};
        for (double a : along)
          xh.insert(xh.end(), {a, dim > 1 ? 0.25 * a : 0.0, dim > 2 ? -0.5 * a : 0.0, 0.5});
        sph::LivePairs scalar;
        const int count =
            sph::select_live_pairs(dim, list, xh.data(), 0, kernel, scalar, SimdTarget::Baseline);
        int expected = 0;
        for (int k = 0; k < length; ++k) {
          const double a = along[k];
          double r2 = a * a;
          if (dim > 1) r2 += 0.0625 * a * a;
          if (dim > 2) r2 += 0.25 * a * a;
          expected += r2 != 0.0 && r2 < 1.0;
        }
        CHECK(count == expected);
        for (SimdTarget t : targets) {
          INFO(length << " pairs, " << dim << "D, kernel " << static_cast<int>(kernel) << ", "
                      << simd_target_name(t));
          sph::LivePairs packed;
          REQUIRE(sph::select_live_pairs(dim, list, xh.data(), 0, kernel, packed, t) == count);
          for (int k = 0; k < count; ++k) {
            CHECK(packed.j[k] == scalar.j[k]);
            CHECK(packed.r2[k] == scalar.r2[k]);
            CHECK(packed.h[k] == scalar.h[k]);
            CHECK(packed.g[k] == scalar.g[k]);
            for (int d = 0; d < dim; ++d) CHECK(packed.x[d][k] == scalar.x[d][k]);
          }
        }
      }
  }
  // A row of 64 pairs whose k-th block of four keeps the lanes of the bits of k: every kept-lane
  // pattern the packed selection can meet, once each.
  {
    std::vector<double> xh{0.0, 0.0, 0.0, 0.5};
    neighbors::PairList list;
    for (int k = 0; k < 64; ++k) {
      const double a = (k / 4 >> (k % 4)) & 1 ? 0.3 + 0.01 * k : 1.5 + 0.01 * k;
      xh.insert(xh.end(), {a, 0.0, 0.0, 0.5});
      list.partner.push_back(k + 1);
    }
    list.offset = {0, 64};
    sph::LivePairs scalar;
    const int count = sph::select_live_pairs(1, list, xh.data(), 0, kernels::SphKernel::CubicSpline,
                                             scalar, SimdTarget::Baseline);
    CHECK(count == 32);
    for (SimdTarget t : targets) {
      INFO("every kept-lane pattern, " << simd_target_name(t));
      sph::LivePairs packed;
      REQUIRE(sph::select_live_pairs(1, list, xh.data(), 0, kernels::SphKernel::CubicSpline, packed,
                                     t) == count);
      for (int k = 0; k < count; ++k) {
        CHECK(packed.j[k] == scalar.j[k]);
        CHECK(packed.x[0][k] == scalar.x[0][k]);
        CHECK(packed.r2[k] == scalar.r2[k]);
        CHECK(packed.g[k] == scalar.g[k]);
      }
    }
  }
  // Every pair term (sph/pair_sums.hpp) through both layouts and both kernels, on each target,
  // with a solid (the strength terms) and with gases alone (the rows without them).
  for (const int dim : {1, 2, 3})
    for (const bool deterministic : {true, false})
      for (const bool gases : {false, true}) {
        sph::Hydro s = mixed_block(dim, dim == 1 ? 40 : dim == 2 ? 16 : 8);
        if (gases) {
          s.materials[0] = s.materials[1];
          sph::update_state(s);
        }
        REQUIRE(s.any_solid() == !gases);
        s.settings.deterministic = deterministic;
        s.settings.kernel =
            dim == 2 ? kernels::SphKernel::WendlandC2 : kernels::SphKernel::CubicSpline;
        sph::refresh_neighbours(s);
        set_simd_target(SimdTarget::Baseline);
        sph::Rates base;
        sph::compute_rates(s, base);
        for (SimdTarget t : targets) {
          INFO(dim << "D, " << (deterministic ? "whole rows, " : "each pair once, ")
                   << (dim == 2 ? "Wendland C2, " : "cubic spline, ")
                   << (gases ? "gases, " : "a solid, ") << simd_target_name(t));
          set_simd_target(t);
          sph::Rates other;
          sph::compute_rates(s, other);
          CHECK(other.dv == base.dv);
          CHECK(other.drho == base.drho);
          CHECK(other.de == base.de);
          CHECK(other.dS == base.dS);
          CHECK(other.grad_v == base.grad_v);
        }
        set_simd_target(preferred_simd_target());
      }
}

TEST_CASE("SPH benchmark: the rates' cost with the live-pair selection of each instruction set",
          "[.][benchmark][sph]") {
  const std::vector<SimdTarget> targets = simd_targets();
  for (const int dim : {2, 3})
    for (const bool deterministic : {false, true}) {
      sph::Hydro s = mixed_block(dim, dim == 2 ? 120 : 24);
      s.settings.deterministic = deterministic;
      sph::refresh_neighbours(s);
      std::vector<double> best(targets.size(), 1e300);
      for (int round = 0; round < 9; ++round)
        for (std::size_t k = 0; k < targets.size(); ++k) {
          set_simd_target(targets[k]);
          sph::Rates r;
          const double t0 = omp_get_wtime();
          sph::compute_rates(s, r);
          best[k] = std::min(best[k], omp_get_wtime() - t0);
        }
      set_simd_target(preferred_simd_target());
      std::printf("  %dD, %s, %d particles, %d thread(s):", dim,
                  deterministic ? "whole rows" : "each pair once", s.particles.owned_count(),
                  omp_get_max_threads());
      for (std::size_t k = 0; k < targets.size(); ++k)
        std::printf(" %s %.2f ms (%.2fx)", simd_target_name(targets[k]), 1e3 * best[k],
                    best[0] / best[k]);
      std::printf("\n");
    }
}
