#pragma once
// Meshfree shape functions and their analytic first derivatives at one point.
//
//  - Reproducing kernel (RK, Liu, Jun & Zhang 1995; [Faraji 2007] eqs. 2-32 to 2-45):
//      phi_I(x) = V_I w_I(x) H(x - x_I)^T b(x),  M(x) b(x) = H(0),
//      M(x) = sum_I V_I w_I H(x - x_I) H(x - x_I)^T.
//  - Moving least squares (EFG, Belytschko, Lu & Gu 1994; [Faraji 2007] eqs. 2-9 to 2-24):
//      phi_I(x) = p(x)^T A(x)^{-1} p(x_I) w_I,  A = sum_I w_I p(x_I) p(x_I)^T,
//      derivatives by the gamma trick  A gamma = p,  A gamma_,i = p_,i - A_,i gamma.
//  - Plain SPH kernel approximation ([Faraji 2007] eq. 2-28): phi_I = V_I W(x - x_I), with W the
//    window normalised to unit integral; no correction, so no consistency at boundaries.
#include "meshfree/core/types.hpp"
#include "meshfree/kernels/window.hpp"

namespace mf::kernels {

enum class Approximation { ReproducingKernel, MovingLeastSquares, Sph };
enum class Basis { Linear, Quadratic };
enum class SupportShape { Circular, Rectangular };

struct ShapeSettings {
  Approximation approximation = Approximation::ReproducingKernel;
  Basis basis = Basis::Linear;
  Window window;
  SupportShape support = SupportShape::Circular;
  int dim = 2; // 1: only x is used; nodes lie on y = 0

  int basis_size() const {
    if (approximation == Approximation::Sph) return 1;
    const bool quad = basis == Basis::Quadratic;
    return dim == 1 ? (quad ? 3 : 2) : (quad ? 6 : 3);
  }
};

/// Read-only view of the nodes: positions, support radii (a_x, a_y; equal for circular
/// supports) and nodal volumes.
struct NodeView {
  const Vec2* x = nullptr;
  const Vec2* radius = nullptr;
  const double* volume = nullptr;
};

/// True when node I's support covers x (w_I(x) > 0).
inline bool covers(const ShapeSettings& s, const NodeView& nodes, int node, const Vec2& x) {
  const Vec2 d = x - nodes.x[node];
  const Vec2& a = nodes.radius[node];
  if (s.dim == 1) return std::abs(d.x()) < a.x();
  if (s.support == SupportShape::Circular) return d.squaredNorm() < a.x() * a.x();
  return std::abs(d.x()) < a.x() && std::abs(d.y()) < a.y();
}

/// Integral of the unnormalised window over its support, for the SPH normalisation.
double window_integral(const ShapeSettings& s, const Vec2& radius);

/// Evaluates phi and (if dphi is not null) its gradient at x for the n nodes listed in
/// `nodes_in_support`. Returns false when the moment matrix is singular (too few or collinear
/// nodes), in which case the outputs are undefined.
bool evaluate_shape(const ShapeSettings& s, const NodeView& nodes, const Vec2& x,
                    const int* nodes_in_support, int n, double* phi, Vec2* dphi);

} // namespace mf::kernels
