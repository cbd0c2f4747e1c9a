#pragma once
// Reproducing-kernel shape functions in three dimensions and their analytic gradients
// (Liu, Jun & Zhang 1995; [Faraji 2007] eqs. 2-32 to 2-45 with the 3D complete basis):
//   phi_I(x) = V_I w_I(x) H(x - x_I)^T b(x),  M(x) b(x) = H(0),
//   M(x) = sum_I V_I w_I H(x - x_I) H(x - x_I)^T,
// H = [1, x, y, z] (linear) or with x^2, xy, xz, y^2, yz, z^2 added (quadratic). The window is
// the plane one's (kernels/window.hpp) of r / a on a sphere, or the product of the three axes'
// windows on a box.
#include "meshfree/core/types.hpp"
#include "meshfree/kernels/shape_functions.hpp"

namespace mf::kernels {

/// The nodes in 3D: positions, support radii per axis (equal for spherical supports) and
/// nodal volumes.
struct NodeView3 {
  const Vec3* x = nullptr;
  const Vec3* radius = nullptr;
  const double* volume = nullptr;
};

/// Terms of the complete 3D basis: 4 (linear) or 10 (quadratic).
inline int basis_size_3d(Basis b) {
  return b == Basis::Quadratic ? 10 : 4;
}

/// True when node I's support covers x (w_I(x) > 0); `Circular` means a sphere.
inline bool covers_3d(SupportShape shape, const NodeView3& nodes, int node, const Vec3& x) {
  const Vec3 d = x - nodes.x[node];
  const Vec3& a = nodes.radius[node];
  if (shape == SupportShape::Circular) return d.squaredNorm() < a.x() * a.x();
  return std::abs(d.x()) < a.x() && std::abs(d.y()) < a.y() && std::abs(d.z()) < a.z();
}

/// phi and (if dphi is not null) its gradient at x for the n nodes listed in `nodes_in_support`,
/// with the approximation, basis, window and support shape of `s` (reproducing kernel only).
/// Returns false when the moment matrix is singular (too few nodes, or nodes in a plane).
bool evaluate_shape_3d(const ShapeSettings& s, const NodeView3& nodes, const Vec3& x,
                       const int* nodes_in_support, int n, double* phi, Vec3* dphi);

} // namespace mf::kernels
