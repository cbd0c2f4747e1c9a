// The volumetric strain of the cell's mean (implicit/volumetric_projection, B-bar) on a table of
// random gradients: every row of a cell gets the cell's mean volumetric strain and keeps its own
// deviatoric strain; the weighted shifts of a cell sum to zero (so a constant stress's pressure
// does no work on them); and the stiffness is the exact derivative of the internal force, K d =
// f(C eps_bar(d)), with test gradients that differ from the trial ones too (VCI). In plane strain
// the in-plane trace takes the cell's mean and the in-plane deviator [e_xx - e_yy, e_xy] is kept.
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/implicit/volumetric_projection.hpp"
#include <catch2/catch.hpp>
#include <random>

using namespace mf;
using namespace mf::implicit;

namespace {

/// Rows 0-2 in cell 7 over nodes {0, 2, 3}, rows 3-4 in cell 4 over nodes {1, 2}.
template <int dim> ShapeTableOf<dim> random_table(std::mt19937& rng, bool test_gradients) {
  using Gradient = typename ShapeTableOf<dim>::Gradient;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random_gradient = [&] {
    Gradient g;
    for (int c = 0; c < dim; ++c) g(c) = u(rng);
    return g;
  };
  ShapeTableOf<dim> t;
  const std::vector<std::vector<int>> nodes{{0, 2, 3}, {0, 2, 3}, {0, 2, 3}, {1, 2}, {1, 2}};
  for (const auto& row : nodes) {
    for (int I : row) {
      t.node.push_back(I);
      t.phi.push_back(u(rng));
      t.dphi.push_back(random_gradient());
      if (test_gradients) t.test_dphi.push_back(random_gradient());
    }
    t.offset.push_back(static_cast<int>(t.node.size()));
  }
  return t;
}

double trace(const Vec6& e) {
  return e(0) + e(1) + e(2);
}

} // namespace

TEST_CASE("cell-mean volumetric strain: the cell's mean trace, own deviator, exact tangent",
          "[solid3d][volumetric]") {
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<int> cell{7, 7, 7, 4, 4};
  const std::vector<double> weight{0.3, 0.5, 0.2, 1.5, 0.5};
  for (const bool vci : {false, true}) {
    CAPTURE(vci);
    const SolidShapeTable plain = random_table<3>(rng, vci);
    SolidShapeTable t = plain;
    project_volumetric_strain(t, cell, weight);
    std::vector<double> d(12);
    for (double& x : d) x = u(rng);
    for (const auto& rows : {std::vector<int>{0, 1, 2}, std::vector<int>{3, 4}}) {
      double mean = 0.0, volume = 0.0;
      for (int r : rows)
        mean += weight[r] * trace(solid_strain_at(plain, r, d)), volume += weight[r];
      mean /= volume;
      for (int r : rows) {
        const Vec6 own = solid_strain_at(plain, r, d), bar = solid_strain_at(t, r, d);
        CHECK(trace(bar) == Approx(mean).margin(1e-14));
        Vec6 dev_own = own, dev_bar = bar;
        dev_own.head<3>().array() -= trace(own) / 3.0;
        dev_bar.head<3>().array() -= trace(bar) / 3.0;
        CHECK((dev_bar - dev_own).norm() <= 1e-14);
      }
      // The weighted test shifts of a cell sum to zero, node by node.
      const int n = t.offset[rows[0] + 1] - t.offset[rows[0]];
      for (int a = 0; a < n; ++a) {
        Vec3 sum = Vec3::Zero();
        for (int r : rows) sum += weight[r] * t.test_shifts(r)[a];
        CHECK(sum.norm() <= 1e-14);
      }
    }
    // K d = f(wC eps_bar(d)) over each row's nodes, wC unsymmetric (non-associated flow).
    Mat6 wC = Mat6::Random();
    std::vector<double> work, K, f;
    for (int r = 0; r < t.rows(); ++r) {
      const int n = t.offset[r + 1] - t.offset[r];
      K.resize(9 * n * n), f.resize(3 * n);
      solid_point_stiffness(t, r, wC, K.data(), work);
      solid_point_force(t, r, wC * solid_strain_at(t, r, d), f.data());
      for (int i = 0; i < 3 * n; ++i) {
        double Kd = 0.0;
        for (int j = 0; j < 3 * n; ++j)
          Kd += K[i * 3 * n + j] * d[3 * t.node[t.offset[r] + j / 3] + j % 3];
        CHECK(Kd == Approx(f[i]).margin(1e-12));
      }
    }
  }
}

TEST_CASE("plane-strain cell-mean volumetric strain: the cell's mean in-plane trace, own in-plane "
          "deviator, exact tangent",
          "[elasticity][volumetric]") {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<int> cell{7, 7, 7, 4, 4};
  const std::vector<double> weight{0.3, 0.5, 0.2, 1.5, 0.5};
  for (const bool vci : {false, true}) {
    CAPTURE(vci);
    const ShapeTable plain = random_table<2>(rng, vci);
    ShapeTable t = plain;
    project_volumetric_strain(t, cell, weight);
    std::vector<double> d(8);
    for (double& x : d) x = u(rng);
    for (const auto& rows : {std::vector<int>{0, 1, 2}, std::vector<int>{3, 4}}) {
      double mean = 0.0, volume = 0.0;
      for (int r : rows) {
        const Vec3 e = strain_at(plain, r, d);
        mean += weight[r] * (e(0) + e(1)), volume += weight[r];
      }
      mean /= volume;
      for (int r : rows) {
        const Vec3 own = strain_at(plain, r, d), bar = strain_at(t, r, d);
        CHECK(bar(0) + bar(1) == Approx(mean).margin(1e-14));
        CHECK(bar(0) - bar(1) == Approx(own(0) - own(1)).margin(1e-14));
        CHECK(bar(2) == Approx(own(2)).margin(1e-14));
      }
      const int n = t.offset[rows[0] + 1] - t.offset[rows[0]];
      for (int a = 0; a < n; ++a) {
        Vec2 sum = Vec2::Zero();
        for (int r : rows) sum += weight[r] * t.test_shifts(r)[a];
        CHECK(sum.norm() <= 1e-14);
      }
    }
    // K d = f(wC eps_bar(d)), with an unsymmetric wC and with a symmetric one (half the blocks
    // computed where the test functions are the trial ones).
    Mat3 unsymmetric = Mat3::Random(), symmetric = unsymmetric + unsymmetric.transpose();
    for (const Mat3& wC : {unsymmetric, symmetric}) {
      std::vector<double> K, f;
      for (int r = 0; r < t.rows(); ++r) {
        const int n = t.offset[r + 1] - t.offset[r];
        K.resize(4 * n * n), f.resize(2 * n);
        point_stiffness(t, r, wC, K.data());
        point_internal_force(t, r, wC * strain_at(t, r, d), f.data());
        for (int i = 0; i < 2 * n; ++i) {
          double Kd = 0.0;
          for (int j = 0; j < 2 * n; ++j)
            Kd += K[i * 2 * n + j] * d[2 * t.node[t.offset[r] + j / 2] + j % 2];
          CHECK(Kd == Approx(f[i]).margin(1e-12));
        }
      }
    }
  }
}
