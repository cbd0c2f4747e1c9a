#include "meshfree/implicit/solid_space.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/parallel_rows.hpp"
#include "meshfree/implicit/shape_tabulation.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

SolidSpace::SolidSpace(SolidNodes nodes, const kernels::ShapeSettings& settings, double dilation)
    : nodes_(std::move(nodes)), settings_(settings) {
  MF_REQUIRE(!nodes_.x.empty(), "the discretisation has no nodes");
  const int n = node_count();
  radius_.resize(n);
  Vec3 lo = nodes_.x[0], hi = nodes_.x[0];
  for (int i = 0; i < n; ++i) {
    const double a = nodes_.spacing[i] * dilation;
    radius_[i] = Vec3(a, a, a);
    reach_ = std::max(reach_, a);
    lo = lo.cwiseMin(nodes_.x[i]);
    hi = hi.cwiseMax(nodes_.x[i]);
  }
  origin_ = lo;
  for (int c = 0; c < 3; ++c)
    dims_(c) = std::max(1, static_cast<int>(std::ceil((hi(c) - lo(c)) / reach_ + 1e-9)));
  std::vector<int> cell(n);
  cell_start_.assign(static_cast<std::size_t>(dims_.prod()) + 1, 0);
  for (int i = 0; i < n; ++i) ++cell_start_[(cell[i] = cell_of(cell_at(nodes_.x[i]))) + 1];
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_node_.resize(n);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n; ++i) cell_node_[fill[cell[i]]++] = i;
}

Eigen::Vector3i SolidSpace::cell_at(const Vec3& x) const {
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a)
    c(a) = std::clamp(static_cast<int>(std::floor((x(a) - origin_(a)) / reach_)), 0, dims_(a) - 1);
  return c;
}

void SolidSpace::nodes_covering(const Vec3& x, std::vector<int>& out) const {
  out.clear();
  const Eigen::Vector3i lo = cell_at(x - Vec3::Constant(reach_));
  const Eigen::Vector3i hi = cell_at(x + Vec3::Constant(reach_));
  const auto v = view();
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) {
        const int c = cell_of({i, j, k});
        for (int s = cell_start_[c]; s < cell_start_[c + 1]; ++s)
          if (kernels::covers_3d(settings_.support, v, cell_node_[s], x))
            out.push_back(cell_node_[s]);
      }
  std::sort(out.begin(), out.end());
}

Csr SolidSpace::support_lists(const std::vector<Vec3>& points) const {
  Csr csr;
  parallel_rows(
      static_cast<int>(points.size()),
      [&](int p, std::vector<int>& row) { nodes_covering(points[p], row); }, csr.offset, csr.index);
  return csr;
}

SolidShapeTable SolidSpace::shape_table(const std::vector<Vec3>& points,
                                        const std::vector<int>& rows, const Csr& support,
                                        bool gradients) const {
  const auto v = view();
  int failed = -1;
  SolidShapeTable t = tabulate_shapes<SolidShapeTable>(
      rows, support, gradients, 3.0 * node_count(), node_count(),
      [&](int p, const int* nb, int count, double* phi, Vec3* dphi) {
        return kernels::evaluate_shape_3d(settings_, v, points[p], nb, count, phi, dphi);
      },
      failed);
  if (failed >= 0) {
    const Vec3& x = points[failed];
    fail("shape functions are undefined at (", x.x(), ", ", x.y(), ", ", x.z(),
         "): ", support.size(failed), " node(s) cover it, too few or in a plane for the ",
         kernels::basis_size_3d(settings_.basis),
         "-term basis; raise discretisation.dilation or refine the nodes there");
  }
  return t;
}

} // namespace mf::implicit
