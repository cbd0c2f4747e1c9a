#pragma once
// The Galerkin weak form of 3D elasticity with penalty essential conditions ([Faraji 2007]
// eq. 2-49 in three dimensions; Belytschko, Lu & Gu 1994 eq. 26):
//   K_IJ = int_Omega B_I^T C B_J dOmega + int_Gamma_u phi_I alpha S phi_J dGamma,
//   f_I  = int_Gamma_t phi_I tbar dGamma + int_Gamma_u phi_I alpha S ubar dGamma
//          + int_Omega phi_I b dOmega,
// Voigt order [xx, yy, zz, yz, xz, xy] with engineering shear strains.
#include "meshfree/core/types.hpp"
#include "meshfree/implicit/solid_space.hpp"
#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/materials/elastic.hpp"
#include <vector>

namespace mf::implicit {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Isotropic elasticity: C = lambda 1 (x) 1 + 2 mu I on engineering shear strains.
Mat6 elastic_matrix_3d(const materials::IsotropicElastic& m);

/// Strain at table row r: eps = sum_I B_I d_I (3 values per node in d), the volumetric part
/// the cell's mean where the table carries the shifts (B-bar).
inline Vec6 solid_strain_at(const SolidShapeTable& t, int r, const std::vector<double>& d) {
  Vec6 e = Vec6::Zero();
  if (const Vec3* shift = t.trial_shifts(r)) {
    double dtheta = 0.0; // mean div u less div u
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
      const double* u = d.data() + 3 * static_cast<std::size_t>(t.node[k]);
      dtheta += shift[k - t.offset[r]].dot(Vec3(u[0], u[1], u[2]));
    }
    e.head<3>().setConstant(dtheta / 3.0);
  }
  for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
    const Vec3& g = t.dphi[k];
    const double* u = d.data() + 3 * static_cast<std::size_t>(t.node[k]);
    e(0) += g.x() * u[0];
    e(1) += g.y() * u[1];
    e(2) += g.z() * u[2];
    e(3) += g.z() * u[1] + g.y() * u[2];
    e(4) += g.z() * u[0] + g.x() * u[2];
    e(5) += g.y() * u[0] + g.x() * u[1];
  }
  return e;
}

/// u^h at table row r.
inline Vec3 solid_displacement_at(const SolidShapeTable& t, int r, const std::vector<double>& d) {
  Vec3 u = Vec3::Zero();
  for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
    const double* v = d.data() + 3 * static_cast<std::size_t>(t.node[k]);
    u += t.phi[k] * Vec3(v[0], v[1], v[2]);
  }
  return u;
}

/// Point r of a table carried to nodal parameters d as a passive material point: the update
/// of its strain from its committed history, which then becomes the update's.
inline materials::StressUpdate3D carry_point(const SolidShapeTable& t, int r,
                                             const std::vector<double>& d,
                                             const materials::ConstitutiveModel& law,
                                             materials::MaterialState& committed) {
  const materials::StressUpdate3D res =
      materials::stress_update_3d(law, solid_strain_at(t, r, d), committed);
  committed = res.state;
  return res;
}

/// The (3n x 3n, row-major) block of point r with n nodes: K_IJ = B~_I^T wC B_J, wC the
/// constitutive or tangent matrix (unsymmetric under non-associated flow) times the point's weight,
/// B~ the test functions' strain matrix; one matrix product of the stacked B~^T wC (3n x 6) and B
/// (6 x 3n), `work` holding them (resized, so a thread keeps one buffer for every point).
void solid_point_stiffness(const SolidShapeTable& t, int r, const Mat6& wC, double* K,
                           std::vector<double>& work);
/// The 3n internal-force values of point r: B~_I^T ws, with ws = weight times stress.
void solid_point_force(const SolidShapeTable& t, int r, const Vec6& ws, double* f);
/// The penalty block alpha w phi_I phi_J on the held components (mask 1) of point r, and its
/// right-hand side alpha w phi_I ubar.
void solid_point_penalty(const SolidShapeTable& t, int r, double alpha_w, const Vec3& mask,
                         const Vec3& ubar, double* K, double* f);

} // namespace mf::implicit
