// The volumetric strain of the cell's mean (implicit/volumetric_projection, B-bar) on a table of
// random gradients: every row of a cell gets the cell's mean volumetric strain and keeps its own
// deviatoric strain; the weighted shifts of a cell sum to zero (so a constant stress's pressure
// does no work on them); and the stiffness is the exact derivative of the internal force, K d =
// f(C eps_bar(d)), with test gradients that differ from the trial ones too (VCI).
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/implicit/volumetric_projection.hpp"
#include <catch2/catch.hpp>
#include <random>

using namespace mf;
using namespace mf::implicit;

namespace {

/// Rows 0-2 in cell 7 over nodes {0, 2, 3}, rows 3-4 in cell 4 over nodes {1, 2}.
SolidShapeTable random_table(std::mt19937& rng, bool test_gradients) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SolidShapeTable t;
  const std::vector<std::vector<int>> nodes{{0, 2, 3}, {0, 2, 3}, {0, 2, 3}, {1, 2}, {1, 2}};
  for (const auto& row : nodes) {
    for (int I : row) {
      t.node.push_back(I);
      t.phi.push_back(u(rng));
      t.dphi.emplace_back(u(rng), u(rng), u(rng));
      if (test_gradients) t.test_dphi.emplace_back(u(rng), u(rng), u(rng));
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
    const SolidShapeTable plain = random_table(rng, vci);
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
