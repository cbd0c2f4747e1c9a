#include "meshfree/kernels/shape_functions.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include <Eigen/Cholesky>
#include <algorithm>

namespace mf::kernels {

namespace {

/// Window value and its gradient with respect to the evaluation point x.
inline double window_with_gradient(const ShapeSettings& s, const Vec2& d, const Vec2& a,
                                   Vec2& grad) {
  const Window& w = s.window;
  if (s.dim == 1) {
    const double z = std::abs(d.x()) / a.x();
    grad = Vec2(w.slope_over_z(z) * d.x() / (a.x() * a.x()), 0.0);
    return w.value(z);
  }
  if (s.support == SupportShape::Circular) {
    const double z = d.norm() / a.x();
    grad = w.slope_over_z(z) / (a.x() * a.x()) * d;
    return w.value(z);
  }
  const double zx = std::abs(d.x()) / a.x(), zy = std::abs(d.y()) / a.y();
  const double wx = w.value(zx), wy = w.value(zy);
  grad = Vec2(w.slope_over_z(zx) * d.x() / (a.x() * a.x()) * wy,
              wx * w.slope_over_z(zy) * d.y() / (a.y() * a.y()));
  return wx * wy;
}

/// Complete polynomial basis in xi and its derivatives d/dxi, d/deta.
/// 1D: [1, xi, xi^2]; 2D: [1, xi, eta, xi^2, xi*eta, eta^2] (Pascal's triangle, eq. 2-4).
inline void basis(int dim, bool quadratic, const Vec2& xi, BasisVec& h, BasisVec& hx,
                  BasisVec& hy) {
  const double x = xi.x(), y = xi.y();
  if (dim == 1) {
    const int m = quadratic ? 3 : 2;
    h.resize(m);
    hx.resize(m);
    hy.setZero(m);
    h(0) = 1.0, h(1) = x, hx(0) = 0.0, hx(1) = 1.0;
    if (quadratic) h(2) = x * x, hx(2) = 2.0 * x;
    return;
  }
  const int m = quadratic ? 6 : 3;
  h.resize(m);
  hx.resize(m);
  hy.resize(m);
  h(0) = 1.0, h(1) = x, h(2) = y;
  hx(0) = 0.0, hx(1) = 1.0, hx(2) = 0.0;
  hy(0) = 0.0, hy(1) = 0.0, hy(2) = 1.0;
  if (quadratic) {
    h(3) = x * x, h(4) = x * y, h(5) = y * y;
    hx(3) = 2.0 * x, hx(4) = y, hx(5) = 0.0;
    hy(3) = 0.0, hy(4) = x, hy(5) = 2.0 * y;
  }
}

/// Rejects moment matrices too close to singular to give meaningful shape functions.
inline bool usable(const Eigen::LLT<BasisMat>& llt) {
  return llt.info() == Eigen::Success && llt.rcond() > 1e-13;
}

double integral_01(const Window& w, int power) { // int_0^1 w(z) z^power dz
  const GaussRule& g = gauss_legendre(20);
  double sum = 0.0;
  for (int half = 0; half < 2; ++half) // split at z = 1/2 where the cubic spline changes piece
    for (std::size_t q = 0; q < g.points.size(); ++q) {
      const double z = 0.25 * (g.points[q] + 1.0) + 0.5 * half;
      sum += 0.25 * g.weights[q] * w.value(z) * (power == 1 ? z : 1.0);
    }
  return sum;
}

bool evaluate_rk(const ShapeSettings& s, const NodeView& nodes, const Vec2& x, const int* nb, int n,
                 double* phi, Vec2* dphi) {
  const int m = s.basis_size();
  const bool quad = s.basis == Basis::Quadratic;
  // Basis scaling: any fixed length gives the same shape functions (the scaling cancels in
  // H(0)^T M^-1 H); the largest support radius keeps M well conditioned.
  double scale = 0.0;
  for (int k = 0; k < n; ++k) scale = std::max(scale, nodes.radius[nb[k]].maxCoeff());
  const double inv = 1.0 / scale;

  BasisMat M = BasisMat::Zero(m, m), Mx = BasisMat::Zero(m, m), My = BasisMat::Zero(m, m);
  BasisVec h, hx, hy;
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    const Vec2 d = x - nodes.x[I];
    Vec2 gw;
    const double w = window_with_gradient(s, d, nodes.radius[I], gw);
    phi[k] = w; // kept for the second pass, which overwrites it with the shape function
    if (dphi) dphi[k] = gw;
    basis(s.dim, quad, d * inv, h, hx, hy);
    hx *= inv;
    hy *= inv;
    const double v = nodes.volume[I];
    const BasisMat hh = h * h.transpose();
    M.noalias() += v * w * hh;
    if (dphi) {
      Mx.noalias() += v * (gw.x() * hh + w * (hx * h.transpose() + h * hx.transpose()));
      My.noalias() += v * (gw.y() * hh + w * (hy * h.transpose() + h * hy.transpose()));
    }
  }
  const Eigen::LLT<BasisMat> llt(M);
  if (!usable(llt)) return false;
  BasisVec e0 = BasisVec::Zero(m);
  e0(0) = 1.0;
  const BasisVec b = llt.solve(e0);
  BasisVec bx, by;
  if (dphi) {
    bx = -llt.solve(Mx * b); // b_,x = -M^-1 M_,x b
    by = -llt.solve(My * b);
  }
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    const Vec2 d = x - nodes.x[I];
    const double w = phi[k];
    const Vec2 gw = dphi ? dphi[k] : Vec2::Zero();
    basis(s.dim, quad, d * inv, h, hx, hy);
    hx *= inv;
    hy *= inv;
    const double v = nodes.volume[I];
    const double c = h.dot(b); // correction function C(x; x - x_I)
    phi[k] = v * c * w;
    if (dphi) {
      dphi[k].x() = v * (gw.x() * c + w * (hx.dot(b) + h.dot(bx)));
      dphi[k].y() = v * (gw.y() * c + w * (hy.dot(b) + h.dot(by)));
    }
  }
  return true;
}

bool evaluate_mls(const ShapeSettings& s, const NodeView& nodes, const Vec2& x, const int* nb,
                  int n, double* phi, Vec2* dphi) {
  const int m = s.basis_size();
  const bool quad = s.basis == Basis::Quadratic;
  // p is written in a frame centred at the evaluation point and scaled by the largest support,
  // both held fixed while differentiating: a complete polynomial basis spans the same space in
  // any such frame, so the shape functions are unchanged and A stays well conditioned however
  // fine the nodes (a global frame loses digits as (L/h)^4 for the quadratic basis).
  double scale = 0.0;
  for (int k = 0; k < n; ++k) scale = std::max(scale, nodes.radius[nb[k]].maxCoeff());
  const double inv = 1.0 / scale;
  BasisMat A = BasisMat::Zero(m, m), Ax = BasisMat::Zero(m, m), Ay = BasisMat::Zero(m, m);
  BasisVec p, px, py, pI, unused1, unused2;
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    Vec2 gw;
    const double w = window_with_gradient(s, x - nodes.x[I], nodes.radius[I], gw);
    basis(s.dim, quad, (nodes.x[I] - x) * inv, pI, unused1, unused2);
    const BasisMat pp = pI * pI.transpose();
    A.noalias() += w * pp;
    if (dphi) {
      Ax.noalias() += gw.x() * pp;
      Ay.noalias() += gw.y() * pp;
    }
  }
  const Eigen::LLT<BasisMat> llt(A);
  if (!usable(llt)) return false;
  basis(s.dim, quad, Vec2::Zero(), p, px, py); // p(x) and its derivatives at the frame origin
  const BasisVec gamma = llt.solve(p);
  BasisVec gx, gy;
  if (dphi) {
    gx = llt.solve(px * inv - Ax * gamma);
    gy = llt.solve(py * inv - Ay * gamma);
  }
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    Vec2 gw;
    const double w = window_with_gradient(s, x - nodes.x[I], nodes.radius[I], gw);
    basis(s.dim, quad, (nodes.x[I] - x) * inv, pI, unused1, unused2);
    const double c = gamma.dot(pI);
    phi[k] = c * w;
    if (dphi) {
      dphi[k].x() = gw.x() * c + w * gx.dot(pI);
      dphi[k].y() = gw.y() * c + w * gy.dot(pI);
    }
  }
  return true;
}

bool evaluate_sph(const ShapeSettings& s, const NodeView& nodes, const Vec2& x, const int* nb,
                  int n, double* phi, Vec2* dphi) {
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    Vec2 gw;
    const double w = window_with_gradient(s, x - nodes.x[I], nodes.radius[I], gw);
    const double c = nodes.volume[I] / window_integral(s, nodes.radius[I]);
    phi[k] = c * w;
    if (dphi) dphi[k] = c * gw;
  }
  return n > 0;
}

} // namespace

double window_integral(const ShapeSettings& s, const Vec2& a) {
  if (s.dim == 1) return 2.0 * a.x() * integral_01(s.window, 0);
  if (s.support == SupportShape::Circular)
    return 2.0 * M_PI * a.x() * a.x() * integral_01(s.window, 1);
  const double i0 = integral_01(s.window, 0);
  return 4.0 * a.x() * a.y() * i0 * i0;
}

bool evaluate_shape(const ShapeSettings& s, const NodeView& nodes, const Vec2& x,
                    const int* nodes_in_support, int n, double* phi, Vec2* dphi) {
  if (n < s.basis_size()) return false;
  switch (s.approximation) {
  case Approximation::ReproducingKernel:
    return evaluate_rk(s, nodes, x, nodes_in_support, n, phi, dphi);
  case Approximation::MovingLeastSquares:
    return evaluate_mls(s, nodes, x, nodes_in_support, n, phi, dphi);
  case Approximation::Sph:
    return evaluate_sph(s, nodes, x, nodes_in_support, n, phi, dphi);
  }
  return false;
}

} // namespace mf::kernels
