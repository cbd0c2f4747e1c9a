#include "meshfree/core/symmetric3.hpp"
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>

namespace {
Eigen::Matrix3d matrix_of(const double a[6]) {
  Eigen::Matrix3d m;
  m << a[0], a[5], a[4], a[5], a[1], a[3], a[4], a[3], a[2];
  return m;
}

/// The positive part by Eigen's iterative solver, the reference.
Eigen::Matrix3d positive_part_reference(const double a[6]) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(matrix_of(a));
  const Eigen::Vector3d plus = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * plus.asDiagonal() * eig.eigenvectors().transpose();
}

/// |closed form - reference| over the largest |eigenvalue|: eigenvalues and positive part.
std::pair<double, double> errors(const double a[6]) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(matrix_of(a));
  const double scale = std::max(eig.eigenvalues().cwiseAbs().maxCoeff(), 1e-300);
  const std::array<double, 3> l = mf::symmetric_eigenvalues(a);
  double value_error = 0.0;
  for (int k = 0; k < 3; ++k) // Eigen's ascend, ours descend
    value_error = std::max(value_error, std::abs(l[k] - eig.eigenvalues()[2 - k]) / scale);
  double plus[6];
  mf::positive_part(a, plus);
  return {value_error,
          (matrix_of(plus) - positive_part_reference(a)).cwiseAbs().maxCoeff() / scale};
}
} // namespace

TEST_CASE("closed-form symmetric 3x3: eigenvalues and positive part equal Eigen's solver",
          "[core]") {
  SECTION("states with repeated, zero and mixed eigenvalues") {
    // Voigt: xx yy zz yz xz xy.
    const double cases[][6] = {{0, 0, 0, 0, 0, 0},
                               {2, 2, 2, 0, 0, 0},
                               {-3, -3, -3, 0, 0, 0},
                               {5, 0, 0, 0, 0, 0},
                               {-5, 0, 0, 0, 0, 0},
                               {5, 5, 0, 0, 0, 0},
                               {0, 0, 0, 0, 0, 4},
                               {1, -1, 0, 0, 0, 0},
                               {3, 1, -2, 0.5, -0.7, 1.1},
                               {-1, -2, -3, 0.1, 0.2, 0.3},
                               {1e6, 1e6, -1, 0, 0, 1},
                               {1, 1, 1, 1, 1, 1},
                               {2, 2, -1, 0, 0, 1e-9},
                               {1e-3, -1e3, 0, 0, 0, 0},
                               {7, 7, 7, 0, 0, 1e-12},
                               // Entries whose cubes underflow or overflow (an SPH particle's first
                               // stress under a blast was of 1e-110 and gave NaN unscaled).
                               {3e-110, 1e-110, -2e-110, 5e-111, -7e-111, 1.1e-110},
                               {0, 0, 0, 0, 0, 1e-160},
                               {3e110, 1e110, -2e110, 5e109, -7e109, 1.1e110}};
    double worst_values = 0.0, worst_plus = 0.0;
    for (const auto& a : cases) {
      const auto [values, plus] = errors(a);
      worst_values = std::max(worst_values, values), worst_plus = std::max(worst_plus, plus);
      INFO(a[0] << " " << a[1] << " " << a[2] << " " << a[3] << " " << a[4] << " " << a[5]);
      CHECK(values < 1e-7); // a repeated eigenvalue costs the trigonometric form sqrt(eps)
      CHECK(plus < 1e-12);
    }
    std::printf("  symmetric 3x3, special states: eigenvalues within %.2e, positive part %.2e\n",
                worst_values, worst_plus);
  }
  SECTION("random states, rotated principal stresses of every sign (fixed seed)") {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst_values = 0.0, worst_plus = 0.0;
    for (int n = 0; n < 20000; ++n) {
      const double a[6] = {u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
      const auto [values, plus] = errors(a);
      worst_values = std::max(worst_values, values), worst_plus = std::max(worst_plus, plus);
    }
    std::printf("  symmetric 3x3, 20,000 random states: eigenvalues within %.2e, positive part "
                "%.2e\n",
                worst_values, worst_plus);
    CHECK(worst_values < 1e-12);
    CHECK(worst_plus < 1e-12);
  }
}
