#include "meshfree/kernels/shape_functions_3d.hpp"
#include <Eigen/Cholesky>
#include <algorithm>

namespace mf::kernels {

namespace {

using Basis3Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 10, 1>;
using Basis3Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 10, 10>;

/// Window value at d = x - x_I and its gradient with respect to x.
inline double window_with_gradient(const ShapeSettings& s, const Vec3& d, const Vec3& a,
                                   Vec3& grad) {
  const Window& w = s.window;
  if (s.support == SupportShape::Circular) {
    const double z = d.norm() / a.x();
    grad = w.slope_over_z(z) / (a.x() * a.x()) * d;
    return w.value(z);
  }
  Vec3 value, slope;
  for (int c = 0; c < 3; ++c) {
    const double z = std::abs(d(c)) / a(c);
    value(c) = w.value(z);
    slope(c) = w.slope_over_z(z) * d(c) / (a(c) * a(c));
  }
  grad = Vec3(slope.x() * value.y() * value.z(), value.x() * slope.y() * value.z(),
              value.x() * value.y() * slope.z());
  return value.prod();
}

/// The complete basis in xi and its derivatives along each axis: [1, x, y, z] and, for the
/// quadratic basis, [x^2, xy, xz, y^2, yz, z^2].
inline void basis(bool quadratic, const Vec3& xi, Basis3Vec& h, Basis3Vec (&dh)[3]) {
  const int m = quadratic ? 10 : 4;
  h.resize(m);
  for (auto& g : dh) g.setZero(m);
  h(0) = 1.0;
  for (int c = 0; c < 3; ++c) h(1 + c) = xi(c), dh[c](1 + c) = 1.0;
  if (!quadratic) return;
  int k = 4;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b, ++k) {
      h(k) = xi(a) * xi(b);
      dh[a](k) += xi(b);
      dh[b](k) += xi(a);
    }
}

} // namespace

bool evaluate_shape_3d(const ShapeSettings& s, const NodeView3& nodes, const Vec3& x, const int* nb,
                       int n, double* phi, Vec3* dphi) {
  const bool quad = s.basis == Basis::Quadratic;
  const int m = basis_size_3d(s.basis);
  if (n < m || s.approximation != Approximation::ReproducingKernel) return false;
  // Any fixed basis scale gives the same shape functions; the largest support keeps M well
  // conditioned (as in 2D).
  double scale = 0.0;
  for (int k = 0; k < n; ++k) scale = std::max(scale, nodes.radius[nb[k]].maxCoeff());
  const double inv = 1.0 / scale;
  Basis3Mat M = Basis3Mat::Zero(m, m), dM[3];
  for (auto& g : dM) g.setZero(m, m);
  Basis3Vec h, dh[3];
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    const Vec3 d = x - nodes.x[I];
    Vec3 gw;
    const double w = window_with_gradient(s, d, nodes.radius[I], gw);
    phi[k] = w; // kept for the second pass, which overwrites it with the shape function
    if (dphi) dphi[k] = gw;
    basis(quad, d * inv, h, dh);
    const double v = nodes.volume[I];
    const Basis3Mat hh = h * h.transpose();
    M.noalias() += v * w * hh;
    if (dphi)
      for (int c = 0; c < 3; ++c)
        dM[c].noalias() +=
            v * (gw(c) * hh + w * inv * (dh[c] * h.transpose() + h * dh[c].transpose()));
  }
  const Eigen::LLT<Basis3Mat> llt(M);
  if (llt.info() != Eigen::Success || llt.rcond() < 1e-13) return false;
  Basis3Vec e0 = Basis3Vec::Zero(m);
  e0(0) = 1.0;
  const Basis3Vec b = llt.solve(e0);
  Basis3Vec db[3];
  if (dphi)
    for (int c = 0; c < 3; ++c) db[c] = -llt.solve(dM[c] * b); // b_,c = -M^-1 M_,c b
  for (int k = 0; k < n; ++k) {
    const int I = nb[k];
    const Vec3 d = x - nodes.x[I];
    const double w = phi[k];
    basis(quad, d * inv, h, dh);
    const double v = nodes.volume[I];
    const double corr = h.dot(b); // correction function C(x; x - x_I)
    phi[k] = v * corr * w;
    if (dphi) {
      const Vec3 gw = dphi[k];
      for (int c = 0; c < 3; ++c)
        dphi[k](c) = v * (gw(c) * corr + w * (inv * dh[c].dot(b) + h.dot(db[c])));
    }
  }
  return true;
}

} // namespace mf::kernels
