#include "meshfree/implicit/solid_forms.hpp"

namespace mf::implicit {

namespace {

/// B_I^T C as a 3 x 6 matrix for gradient g (the rows of B_I^T are the strains of a unit
/// displacement along x, y and z).
Eigen::Matrix<double, 3, 6> bt_times(const Vec3& g, const Mat6& C) {
  Eigen::Matrix<double, 3, 6> B;
  B << g.x(), 0.0, 0.0, 0.0, g.z(), g.y(), //
      0.0, g.y(), 0.0, g.z(), 0.0, g.x(),  //
      0.0, 0.0, g.z(), g.y(), g.x(), 0.0;
  return B * C;
}

Eigen::Matrix<double, 6, 3> strain_matrix_3d(const Vec3& g) {
  Eigen::Matrix<double, 6, 3> B;
  B << g.x(), 0.0, 0.0,  //
      0.0, g.y(), 0.0,   //
      0.0, 0.0, g.z(),   //
      0.0, g.z(), g.y(), //
      g.z(), 0.0, g.x(), //
      g.y(), g.x(), 0.0;
  return B;
}

} // namespace

Mat6 elastic_matrix_3d(const materials::IsotropicElastic& m) {
  const double mu = m.E / (2.0 * (1.0 + m.nu));
  const double lambda = m.E * m.nu / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu));
  Mat6 C = Mat6::Zero();
  C.topLeftCorner<3, 3>().setConstant(lambda);
  for (int i = 0; i < 3; ++i) C(i, i) += 2.0 * mu, C(3 + i, 3 + i) = mu;
  return C;
}

void solid_point_stiffness(const SolidShapeTable& t, int r, const Mat6& wC, double* K,
                           std::vector<double>& work) {
  const int first = t.offset[r], n = t.offset[r + 1] - first;
  const Vec3* test = t.test_gradients(r);
  work.resize(36 * static_cast<std::size_t>(n));
  Eigen::Map<Eigen::MatrixXd> BtC(work.data(), 3 * n, 6);
  Eigen::Map<Eigen::MatrixXd> B(work.data() + 18 * static_cast<std::size_t>(n), 6, 3 * n);
  for (int a = 0; a < n; ++a) {
    BtC.middleRows<3>(3 * a) = bt_times(test[a], wC);
    B.middleCols<3>(3 * a) = strain_matrix_3d(t.dphi[first + a]);
  }
  if (const Vec3* shift = t.trial_shifts(r)) { // B-bar: B + m shift^T / 3, and so the test side
    const Vec3* test_shift = t.test_shifts(r);
    const Eigen::Matrix<double, 1, 6> mC = wC.topRows<3>().colwise().sum() / 3.0;
    for (int a = 0; a < n; ++a) {
      BtC.middleRows<3>(3 * a) += test_shift[a] * mC;
      for (int i = 0; i < 3; ++i) B.block<3, 1>(0, 3 * a + i).array() += shift[a](i) / 3.0;
    }
  }
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(K, 3 * n,
                                                                                         3 * n);
  out.noalias() = BtC * B;
}

void solid_point_force(const SolidShapeTable& t, int r, const Vec6& ws, double* f) {
  const int n = t.offset[r + 1] - t.offset[r];
  const Vec3* test = t.test_gradients(r);
  for (int a = 0; a < n; ++a) {
    const Vec3& g = test[a];
    f[3 * a] = g.x() * ws(0) + g.z() * ws(4) + g.y() * ws(5);
    f[3 * a + 1] = g.y() * ws(1) + g.z() * ws(3) + g.x() * ws(5);
    f[3 * a + 2] = g.z() * ws(2) + g.y() * ws(3) + g.x() * ws(4);
  }
  if (const Vec3* shift = t.test_shifts(r)) { // B-bar: the mean pressure's share
    const double p = (ws(0) + ws(1) + ws(2)) / 3.0;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) f[3 * a + i] += p * shift[a](i);
  }
}

void solid_point_penalty(const SolidShapeTable& t, int r, double alpha_w, const Vec3& mask,
                         const Vec3& ubar, double* K, double* f) {
  const int first = t.offset[r], n = t.offset[r + 1] - first;
  const int cols = 3 * n;
  for (int a = 0; a < n; ++a) {
    const double pa = alpha_w * t.phi[first + a];
    for (int c = 0; c < 3; ++c) f[3 * a + c] = pa * mask(c) * ubar(c);
    for (int b = 0; b < n; ++b) {
      const double v = pa * t.phi[first + b];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K[(3 * a + i) * cols + 3 * b + j] = i == j ? v * mask(i) : 0.0;
    }
  }
}

} // namespace mf::implicit
