#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/core/error.hpp"

namespace mf::implicit {

namespace {

/// Writes the 2x2 block k into row-major K (2n x 2n) at block (i, j).
void put_block(double* K, int n, int i, int j, const Mat2& k) {
  double* row0 = K + (2 * i) * (2 * n) + 2 * j;
  double* row1 = row0 + 2 * n;
  row0[0] = k(0, 0), row0[1] = k(0, 1);
  row1[0] = k(1, 0), row1[1] = k(1, 1);
}

/// B + [1 1 0]^T shift^T / 2: a node's strain matrix with its shift to the cell's mean
/// volumetric strain (implicit/volumetric_projection), or B without one.
Eigen::Matrix<double, 3, 2> shifted_strain_matrix(const Vec2& g, const Vec2* shift) {
  Eigen::Matrix<double, 3, 2> B = strain_matrix(g);
  if (shift) B.topRows<2>().rowwise() += shift->transpose() / 2.0;
  return B;
}

} // namespace

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
  const Vec2* shift = t.trial_shifts(r);
  for (int j = 0; j < n; ++j) CB[j] = wC * shifted_strain_matrix(g[j], shift ? shift + j : nullptr);
  // Where C is symmetric (elasticity, and the consistent tangent of associative plasticity) and
  // the test functions are the trial functions, K_JI = K_IJ^T and half the blocks are computed;
  // corrected test functions (a Petrov-Galerkin form) and a non-associated flow's tangent need
  // every block.
  const bool symmetric = t.test_dphi.empty() && wC == wC.transpose();
  const Vec2* h = t.test_gradients(r);
  const Vec2* test_shift = t.test_shifts(r);
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix<double, 3, 2> Bi =
        shifted_strain_matrix(h[i], test_shift ? test_shift + i : nullptr);
    for (int j = symmetric ? i : 0; j < n; ++j) {
      const Mat2 kij = Bi.transpose() * CB[j];
      put_block(K, n, i, j, kij);
      // On the diagonal too: the transpose written last, as the results have always had it.
      if (symmetric) put_block(K, n, j, i, kij.transpose());
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
  if (const Vec2* shift = t.test_shifts(r)) { // B-bar: the in-plane mean stress's share
    const double p = (ws(0) + ws(1)) / 2.0;
    for (int i = 0; i < n; ++i) {
      f[2 * i] += p * shift[i].x();
      f[2 * i + 1] += p * shift[i].y();
    }
  }
}

void add_internal_force(const ShapeTable& t, const PointGroups& groups,
                        const std::vector<double>& weight, const std::vector<Vec3>& stress,
                        const VectorAdder& add) {
  MF_REQUIRE(groups.rows() == t.rows(), "add_internal_force: points not grouped");
  std::vector<std::vector<double>> f(PointGroups::threads());
  groups.for_each([&](int r, int thread) {
    const int n = t.offset[r + 1] - t.offset[r];
    f[thread].resize(2 * n);
    point_internal_force(t, r, weight[r] * stress[r], f[thread].data());
    add(t.node.data() + t.offset[r], n, f[thread].data());
  });
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
