#pragma once
// What every constitutive model of a Galerkin point returns and carries: the committed history
// at a material point and the result of one stress update (stress, algorithmic tangent, trial
// history), and the Voigt algebra the models share.
//
// Voigt order 3D [xx, yy, zz, yz, xz, xy], 2D [xx, yy, xy]; strains with engineering shear,
// stresses (and stress-like tensors such as a unit normal to a yield surface) without.
#include "meshfree/core/types.hpp"
#include <cmath>

namespace mf::materials {

/// The 3D Voigt indices of a plane state's [xx, yy, xy].
constexpr int kPlane[3] = {0, 1, 5};

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Committed history at a material point. Every model keeps its plastic strain and an equivalent
/// plastic strain (J2: sqrt(2/3) |eps_p|; Drucker-Prager: its hardening variable); J2 with
/// kinematic hardening also its back stress (zero for the others).
struct MaterialState {
  Vec6 plastic_strain = Vec6::Zero(); // engineering shear components
  Vec6 back_stress = Vec6::Zero();    // deviatoric, stress-like
  double alpha = 0.0;                 // equivalent plastic strain
};

struct StressUpdate3D {
  Vec6 stress = Vec6::Zero();
  Mat6 tangent = Mat6::Zero();
  MaterialState state;
  bool plastic = false;
};

struct StressUpdate2D {
  Vec3 stress = Vec3::Zero(); // [xx, yy, xy]
  double stress_zz = 0.0;
  double strain_zz = 0.0; // total eps_zz (0 in plane strain)
  Mat3 tangent = Mat3::Zero();
  MaterialState state;
  bool plastic = false;
};

namespace voigt {

/// m = [1 1 1 0 0 0]
inline Vec6 unit_trace() {
  Vec6 m = Vec6::Zero();
  m.head<3>().setOnes();
  return m;
}

/// Deviatoric part of a stress-like Voigt vector.
inline Vec6 deviator(const Vec6& s) {
  Vec6 d = s;
  d.head<3>().array() -= s.head<3>().sum() / 3.0;
  return d;
}

/// Tensor norm of a stress-like Voigt vector: sqrt(s : s).
inline double tensor_norm(const Vec6& s) {
  return std::sqrt(s.head<3>().squaredNorm() + 2.0 * s.tail<3>().squaredNorm());
}

/// Stress-like to strain-like (engineering shear) Voigt.
inline Vec6 engineering(const Vec6& t) {
  Vec6 e = t;
  e.tail<3>() *= 2.0;
  return e;
}

/// The deviatoric projector as a map from an engineering strain to a stress-like deviator:
/// dev(eps) = I_dev eps (shear rows halved).
inline Mat6 deviatoric_projector() {
  Mat6 I_sym = Mat6::Identity();
  I_sym.diagonal().tail<3>().setConstant(0.5);
  const Vec6 m = unit_trace();
  return I_sym - m * m.transpose() / 3.0;
}

/// Embeds a plane strain [xx, yy, xy] and eps_zz into a 3D strain.
inline Vec6 embed(const Vec3& e, double ezz) {
  Vec6 s = Vec6::Zero();
  s << e(0), e(1), ezz, 0.0, 0.0, e(2);
  return s;
}

/// The plane part of a 3D update at the out-of-plane strain ezz.
inline StressUpdate2D reduce(const StressUpdate3D& r3, double ezz) {
  StressUpdate2D r;
  for (int a = 0; a < 3; ++a) {
    r.stress(a) = r3.stress(kPlane[a]);
    for (int b = 0; b < 3; ++b) r.tangent(a, b) = r3.tangent(kPlane[a], kPlane[b]);
  }
  r.stress_zz = r3.stress(2);
  r.strain_zz = ezz;
  r.state = r3.state;
  r.plastic = r3.plastic;
  return r;
}

} // namespace voigt
} // namespace mf::materials
