#include "meshfree/implicit/elasticity.hpp"

namespace mf::implicit {

void add_internal_force(const ShapeTable& t, const std::vector<double>& weight,
                        const std::vector<Vec3>& stress, const VectorAdder& add) {
  std::vector<double> f;
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const Vec2* g = t.dphi.data() + t.offset[r];
    const Vec3 ws = weight[r] * stress[r];
    f.resize(2 * n);
    for (int i = 0; i < n; ++i) {
      f[2 * i] = g[i].x() * ws(0) + g[i].y() * ws(2);
      f[2 * i + 1] = g[i].y() * ws(1) + g[i].x() * ws(2);
    }
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
