#pragma once
// Fixed-size Eigen types used across the code, and the Voigt conventions of docs/architecture.md:
// 2D Voigt order [xx, yy, xy] with engineering shear strain gamma_xy = 2 eps_xy.
#include <Eigen/Core>
#include <Eigen/Dense>

namespace mf {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

/// Small dense matrices whose size is known only at run time but bounded (RK moment matrices:
/// at most the 6 terms of a complete quadratic basis in 2D). They live on the stack.
constexpr int kMaxBasis = 6;
using BasisVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBasis, 1>;
using BasisMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBasis, kMaxBasis>;

struct BoundingBox {
  Vec2 lo{0.0, 0.0};
  Vec2 hi{0.0, 0.0};
  bool contains(const Vec2& p, double tol = 0.0) const {
    return p.x() >= lo.x() - tol && p.x() <= hi.x() + tol && p.y() >= lo.y() - tol &&
           p.y() <= hi.y() + tol;
  }
  Vec2 size() const { return hi - lo; }
};

} // namespace mf
