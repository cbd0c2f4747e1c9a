#include "meshfree/fem/tet_locator.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>

namespace mf::fem {

namespace {

constexpr double kInsideTolerance = 1e-9; // natural coordinates

bool inside(const Vec3& xi, double tol) {
  return xi.minCoeff() >= -tol && xi.sum() <= 1.0 + tol;
}

} // namespace

TetLocator::TetLocator(const TetMesh& mesh) : mesh_(&mesh) {
  const int ne = mesh.element_count();
  MF_REQUIRE(ne > 0, "TetLocator: the mesh has no elements");
  lo_.resize(ne);
  hi_.resize(ne);
  double mean = 0.0;
  for (int e = 0; e < ne; ++e) {
    const int* n = mesh.element(e);
    Vec3 lo = mesh.x[n[0]], hi = lo;
    auto grow = [&](const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); };
    for (int a = 1; a < 4; ++a) grow(mesh.x[n[a]]);
    if (mesh.quadratic)
      for (int k = 0; k < 6; ++k) {
        const int* ends = tet_edge_corners(k);
        grow(2.0 * mesh.x[n[4 + k]] - 0.5 * (mesh.x[n[ends[0]]] + mesh.x[n[ends[1]]]));
      }
    lo_[e] = lo, hi_[e] = hi;
    mean += (hi - lo).maxCoeff() / ne;
    origin_ = e == 0 ? lo : origin_.cwiseMin(lo);
  }
  Vec3 top = hi_[0];
  for (const Vec3& h : hi_) top = top.cwiseMax(h);
  cell_ = std::max(mean, 1e-12 * (top - origin_).maxCoeff());
  // At most about 8 cells per element, so that a graded mesh's small elements do not make the
  // grid large.
  while (true) {
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) cells *= std::floor((top(d) - origin_(d)) / cell_) + 1.0;
    if (cells <= 8.0 * ne + 64.0) break;
    cell_ *= 1.25;
  }
  for (int d = 0; d < 3; ++d) dims_[d] = static_cast<int>((top(d) - origin_(d)) / cell_) + 1;
  const auto index = [&](const Vec3& p, int d) {
    return std::clamp(static_cast<int>(std::floor((p(d) - origin_(d)) / cell_)), 0, dims_[d] - 1);
  };
  std::vector<std::vector<int>> lists(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2]);
  for (int e = 0; e < ne; ++e)
    for (int k = index(lo_[e], 2); k <= index(hi_[e], 2); ++k)
      for (int j = index(lo_[e], 1); j <= index(hi_[e], 1); ++j)
        for (int i = index(lo_[e], 0); i <= index(hi_[e], 0); ++i)
          lists[(static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i].push_back(e);
  start_.assign(1, 0);
  for (const auto& l : lists) {
    element_.insert(element_.end(), l.begin(), l.end());
    start_.push_back(static_cast<int>(element_.size()));
  }
}

int TetLocator::cell_of(const Vec3& x) const {
  int c[3];
  for (int d = 0; d < 3; ++d)
    c[d] = std::clamp(static_cast<int>(std::floor((x(d) - origin_(d)) / cell_)), 0, dims_[d] - 1);
  return (c[2] * dims_[1] + c[1]) * dims_[0] + c[0];
}

bool TetLocator::natural(int e, const Vec3& x, Vec3& xi) const {
  const TetMesh& mesh = *mesh_;
  const int* n = mesh.element(e);
  Mat3 J;
  for (int a = 0; a < 3; ++a) J.col(a) = mesh.x[n[a + 1]] - mesh.x[n[0]];
  xi = J.inverse() * (x - mesh.x[n[0]]);
  if (!mesh.quadratic) return true;
  double N[kTetMaxNodes];
  Vec3 dN[kTetMaxNodes];
  for (int it = 0; it < 30; ++it) {
    tet_shape_functions(true, xi, N, dN);
    Vec3 r = -x;
    J.setZero();
    for (int a = 0; a < 10; ++a) r += N[a] * mesh.x[n[a]], J += mesh.x[n[a]] * dN[a].transpose();
    if (!(J.determinant() > 0.0)) return false;
    const Vec3 step = J.inverse() * r;
    xi -= step;
    if (!inside(xi, 1.0)) return false; // wandered off: not this element
    // Quadratic convergence: after a step this small the error is at rounding level.
    if (step.lpNorm<Eigen::Infinity>() < 1e-10) return true;
  }
  return false;
}

bool TetLocator::locate(const Vec3& x, int& element, Vec3& xi) const {
  const int c = cell_of(x);
  for (int k = start_[c]; k < start_[c + 1]; ++k) {
    const int e = element_[k];
    const double tol = 1e-6 * (hi_[e] - lo_[e]).maxCoeff();
    if ((x.array() < lo_[e].array() - tol).any() || (x.array() > hi_[e].array() + tol).any())
      continue;
    Vec3 z;
    if (natural(e, x, z) && inside(z, kInsideTolerance)) {
      element = e;
      xi = z;
      return true;
    }
  }
  return false;
}

} // namespace mf::fem
