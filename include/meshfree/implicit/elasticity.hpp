#pragma once
// Galerkin weak form of plane elasticity with penalty essential conditions (the thesis'
// eq. 2-49; Belytschko, Lu & Gu 1994 eq. 26 with the penalty in place of multipliers):
//   K_IJ = int_Omega B_I^T C B_J t dOmega + int_Gamma_u phi_I alpha S phi_J t dGamma,
//   f_I  = int_Gamma_t phi_I tbar t dGamma + int_Gamma_u phi_I alpha S ubar t dGamma
//          + int_Omega phi_I b t dOmega,
// with S the diagonal selector of the constrained components. Contributions leave through
// callbacks so that the same loops serve any matrix back end.
#include "meshfree/core/types.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include <functional>
#include <vector>

namespace mf::implicit {

/// Adds a dense (2n x 2n, row-major) block on the 2 DOFs of each of n nodes.
using MatrixAdder = std::function<void(const int* nodes, int n, const double* block)>;
/// Adds a 2n vector on the 2 DOFs of each of n nodes.
using VectorAdder = std::function<void(const int* nodes, int n, const double* values)>;

/// Strain-displacement matrix B_I of one node (the thesis' eq. 2-47), Voigt [xx, yy, 2xy].
inline Eigen::Matrix<double, 3, 2> strain_matrix(const Vec2& g) {
  Eigen::Matrix<double, 3, 2> B;
  B << g.x(), 0.0, 0.0, g.y(), g.y(), g.x();
  return B;
}

/// K_IJ = sum_r weight[r] B_I^T C(r) B_J: the elastic stiffness (C constant) or the tangent of a
/// nonlinear material (C(r) its algorithmic tangent at point r). `C_at(r)` returns a Mat3.
template <class MaterialAt>
void add_tangent(const ShapeTable& t, const std::vector<double>& weight, MaterialAt&& C_at,
                 const MatrixAdder& add) {
  std::vector<double> K;
  std::vector<Eigen::Matrix<double, 3, 2>> CB; // w C B_J for each node of the point
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const int* nodes = t.node.data() + t.offset[r];
    const Vec2* g = t.dphi.data() + t.offset[r];
    const Mat3 wC = weight[r] * C_at(r);
    K.assign(4 * n * n, 0.0);
    CB.resize(n);
    for (int j = 0; j < n; ++j) CB[j] = wC * strain_matrix(g[j]);
    for (int i = 0; i < n; ++i) {
      const Eigen::Matrix<double, 3, 2> Bi = strain_matrix(g[i]);
      for (int j = 0; j < n; ++j) {
        const Mat2 kij = Bi.transpose() * CB[j];
        double* row0 = K.data() + (2 * i) * (2 * n) + 2 * j;
        double* row1 = row0 + 2 * n;
        row0[0] = kij(0, 0), row0[1] = kij(0, 1);
        row1[0] = kij(1, 0), row1[1] = kij(1, 1);
      }
    }
    add(nodes, n, K.data());
  }
}

/// Elastic stiffness with one constitutive matrix for every point.
inline void add_stiffness(const ShapeTable& t, const std::vector<double>& weight, const Mat3& C,
                          const MatrixAdder& add) {
  add_tangent(
      t, weight, [&C](int) -> const Mat3& { return C; }, add);
}

/// Internal force f_I = sum_r weight[r] B_I^T sigma[r].
void add_internal_force(const ShapeTable& table, const std::vector<double>& weight,
                        const std::vector<Vec3>& stress, const VectorAdder& add);

/// Penalty stiffness alpha * phi_I phi_J on the components selected by `mask` (1 or 0 each),
/// and the matching right-hand side alpha * phi_I * ubar[r].
void add_penalty(const ShapeTable& table, const std::vector<double>& weight, const Vec2& mask,
                 double alpha, const std::vector<Vec2>& ubar, const MatrixAdder& add_matrix,
                 const VectorAdder& add_vector);

/// Load vector phi_I * load[r] (traction or body force density).
void add_load(const ShapeTable& table, const std::vector<double>& weight,
              const std::vector<Vec2>& load, const VectorAdder& add);

/// Strain-displacement product at table row r: eps = sum_I B_I d_I, Voigt [xx, yy, 2xy].
inline Vec3 strain_at(const ShapeTable& t, int r, const std::vector<double>& d) {
  Vec3 e = Vec3::Zero();
  for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
    const int I = t.node[k];
    const Vec2& g = t.dphi[k];
    e(0) += g.x() * d[2 * I];
    e(1) += g.y() * d[2 * I + 1];
    e(2) += g.y() * d[2 * I] + g.x() * d[2 * I + 1];
  }
  return e;
}

/// Approximated displacement at table row r: u^h = sum_I phi_I d_I (not the nodal parameter:
/// meshfree shape functions are not interpolating).
inline Vec2 displacement_at(const ShapeTable& t, int r, const std::vector<double>& d) {
  Vec2 u = Vec2::Zero();
  for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
    const int I = t.node[k];
    u += t.phi[k] * Vec2(d[2 * I], d[2 * I + 1]);
  }
  return u;
}

} // namespace mf::implicit
