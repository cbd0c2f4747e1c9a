#include "meshfree/implicit/elasticity.hpp"

namespace mf::implicit {

void point_stiffness(const ShapeTable& t, int r, const Mat3& wC, double* K) {
  const int n = t.offset[r + 1] - t.offset[r];
  const Vec2* g = t.dphi.data() + t.offset[r];
  // w C B_J for each node: on the stack for the usual supports, on the heap for crowded ones.
  constexpr int kOnStack = 64;
  Eigen::Matrix<double, 3, 2> stack[kOnStack];
  std::vector<Eigen::Matrix<double, 3, 2>> heap;
  Eigen::Matrix<double, 3, 2>* CB = stack;
  if (n > kOnStack) {
    heap.resize(n);
    CB = heap.data();
  }
  for (int j = 0; j < n; ++j) CB[j] = wC * strain_matrix(g[j]);
  if (!t.test_dphi.empty()) {
    // Corrected test functions (a Petrov-Galerkin form): every block on its own.
    const Vec2* h = t.test_gradients(r);
    for (int i = 0; i < n; ++i) {
      const Eigen::Matrix<double, 3, 2> Bi = strain_matrix(h[i]);
      for (int j = 0; j < n; ++j) {
        const Mat2 kij = Bi.transpose() * CB[j];
        double* ij0 = K + (2 * i) * (2 * n) + 2 * j;
        double* ij1 = ij0 + 2 * n;
        ij0[0] = kij(0, 0), ij0[1] = kij(0, 1);
        ij1[0] = kij(1, 0), ij1[1] = kij(1, 1);
      }
    }
    return;
  }
  // C is symmetric (elasticity, and the consistent tangent of associative plasticity), so
  // K_JI = K_IJ^T: half the blocks are computed.
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix<double, 3, 2> Bi = strain_matrix(g[i]);
    for (int j = i; j < n; ++j) {
      const Mat2 kij = Bi.transpose() * CB[j];
      double* ij0 = K + (2 * i) * (2 * n) + 2 * j;
      double* ij1 = ij0 + 2 * n;
      double* ji0 = K + (2 * j) * (2 * n) + 2 * i;
      double* ji1 = ji0 + 2 * n;
      ij0[0] = kij(0, 0), ij0[1] = kij(0, 1);
      ij1[0] = kij(1, 0), ij1[1] = kij(1, 1);
      ji0[0] = kij(0, 0), ji0[1] = kij(1, 0);
      ji1[0] = kij(0, 1), ji1[1] = kij(1, 1);
    }
  }
}

void point_internal_force(const ShapeTable& t, int r, const Vec3& ws, double* f) {
  const int n = t.offset[r + 1] - t.offset[r];
  const Vec2* g = t.test_gradients(r);
  for (int i = 0; i < n; ++i) {
    f[2 * i] = g[i].x() * ws(0) + g[i].y() * ws(2);
    f[2 * i + 1] = g[i].y() * ws(1) + g[i].x() * ws(2);
  }
}

void add_internal_force(const ShapeTable& t, const std::vector<double>& weight,
                        const std::vector<Vec3>& stress, const VectorAdder& add) {
  std::vector<double> f;
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    f.resize(2 * n);
    point_internal_force(t, r, weight[r] * stress[r], f.data());
    add(t.node.data() + t.offset[r], n, f.data());
  }
}

void add_penalty(const ShapeTable& t, const std::vector<double>& weight, const Vec2& mask,
                 double alpha, const std::vector<Vec2>& ubar, const MatrixAdder& add_matrix,
                 const VectorAdder& add_vector) {
  std::vector<double> K, f;
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const int* nodes = t.node.data() + t.offset[r];
    const double* phi = t.phi.data() + t.offset[r];
    const double aw = alpha * weight[r];
    K.assign(4 * n * n, 0.0);
    f.assign(2 * n, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double v = aw * phi[i] * phi[j];
        K[(2 * i) * (2 * n) + 2 * j] = v * mask.x();
        K[(2 * i + 1) * (2 * n) + 2 * j + 1] = v * mask.y();
      }
      f[2 * i] = aw * phi[i] * mask.x() * ubar[r].x();
      f[2 * i + 1] = aw * phi[i] * mask.y() * ubar[r].y();
    }
    add_matrix(nodes, n, K.data());
    add_vector(nodes, n, f.data());
  }
}

void add_load(const ShapeTable& t, const std::vector<double>& weight, const std::vector<Vec2>& load,
              const VectorAdder& add) {
  std::vector<double> f;
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const double* phi = t.phi.data() + t.offset[r];
    f.resize(2 * n);
    for (int i = 0; i < n; ++i) {
      f[2 * i] = weight[r] * phi[i] * load[r].x();
      f[2 * i + 1] = weight[r] * phi[i] * load[r].y();
    }
    add(t.node.data() + t.offset[r], n, f.data());
  }
}

} // namespace mf::implicit
