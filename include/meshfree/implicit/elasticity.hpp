#pragma once
// Galerkin weak form of plane elasticity with penalty essential conditions ([Faraji 2007]
// eq. 2-49; Belytschko, Lu & Gu 1994 eq. 26 with the penalty in place of multipliers):
//   K_IJ = int_Omega B_I^T C B_J t dOmega + int_Gamma_u phi_I alpha S phi_J t dGamma,
//   f_I  = int_Gamma_t phi_I tbar t dGamma + int_Gamma_u phi_I alpha S ubar t dGamma
//          + int_Omega phi_I b t dOmega,
// with S the diagonal selector of the constrained components. Contributions leave through
// callbacks so that the same loops serve any matrix back end.
#include "meshfree/core/types.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/point_groups.hpp"
#include <functional>
#include <vector>

namespace mf::implicit {

/// Adds a dense (2n x 2n, row-major) block on the 2 DOFs of each of n nodes.
using MatrixAdder = std::function<void(const int* nodes, int n, const double* block)>;
/// Adds a 2n vector on the 2 DOFs of each of n nodes.
using VectorAdder = std::function<void(const int* nodes, int n, const double* values)>;

/// Strain-displacement matrix B_I of one node ([Faraji 2007] eq. 2-47), Voigt [xx, yy, 2xy].
inline Eigen::Matrix<double, 3, 2> strain_matrix(const Vec2& g) {
  Eigen::Matrix<double, 3, 2> B;
  B << g.x(), 0.0, 0.0, g.y(), g.y(), g.x();
  return B;
}

/// The 2n x 2n block (row-major) of one point r of the table with n nodes: K_IJ = B~_I^T wC B_J,
/// with wC the constitutive (or algorithmic tangent) matrix times the point's weight (half the
/// blocks computed where it is symmetric), and B~ the test functions' strain matrix (B itself
/// unless the table holds corrected test gradients); both with the shifts to the cell's mean
/// volumetric strain, B + [1 1 0]^T shift^T / 2, where the table has them. `K` has room for
/// 4 n^2 values.
void point_stiffness(const ShapeTable& t, int r, const Mat3& wC, double* K);

/// The 2n internal-force values of point r of the table: w B~_I^T sigma (B~ as in
/// point_stiffness), with ws = w sigma.
void point_internal_force(const ShapeTable& t, int r, const Vec3& ws, double* f);

/// Internal force f_I = sum_r weight[r] B~_I^T sigma[r] (B~ as in point_stiffness), the points
/// taken in `groups` (threads at once; `add` must take rows of different nodes concurrently).
void add_internal_force(const ShapeTable& table, const PointGroups& groups,
                        const std::vector<double>& weight, const std::vector<Vec3>& stress,
                        const VectorAdder& add);

/// Penalty stiffness alpha * phi_I phi_J on the components selected by `mask` (1 or 0 each),
/// and the matching right-hand side alpha * phi_I * ubar[r].
void add_penalty(const ShapeTable& table, const std::vector<double>& weight, const Vec2& mask,
                 double alpha, const std::vector<Vec2>& ubar, const MatrixAdder& add_matrix,
                 const VectorAdder& add_vector);

/// Load vector phi_I * load[r] (traction or body force density).
void add_load(const ShapeTable& table, const std::vector<double>& weight,
              const std::vector<Vec2>& load, const VectorAdder& add);

/// Strain-displacement product at table row r: eps = sum_I B_I d_I, Voigt [xx, yy, 2xy]; the
/// in-plane volumetric part the cell's mean where the table carries the shifts (plane-strain
/// B-bar, implicit/volumetric_projection).
inline Vec3 strain_at(const ShapeTable& t, int r, const std::vector<double>& d) {
  Vec3 e = Vec3::Zero();
  if (const Vec2* shift = t.trial_shifts(r)) {
    double dtheta = 0.0; // mean div u less div u
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
      const int I = t.node[k];
      dtheta += shift[k - t.offset[r]].dot(Vec2(d[2 * I], d[2 * I + 1]));
    }
    e.head<2>().setConstant(dtheta / 2.0);
  }
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
