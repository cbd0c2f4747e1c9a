#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <atomic>

namespace mf::implicit {

MeshfreeSpace::MeshfreeSpace(geometry::NodeCloud cloud, const kernels::ShapeSettings& settings,
                             const Vec2& dilation)
    : cloud_(std::move(cloud)), settings_(settings) {
  MF_REQUIRE(!cloud_.x.empty(), "the discretisation has no nodes");
  radius_.resize(cloud_.x.size());
  for (std::size_t i = 0; i < cloud_.x.size(); ++i) {
    radius_[i] = cloud_.spacing[i] * dilation;
    max_radius_ = std::max(max_radius_, radius_[i].maxCoeff());
  }
  grid_ = neighbors::PointGrid(cloud_.x, max_radius_);
}

void MeshfreeSpace::nodes_covering(const Vec2& x, std::vector<int>& out) const {
  out.clear();
  const auto v = view();
  grid_.for_each_in_box(x - Vec2(max_radius_, max_radius_), x + Vec2(max_radius_, max_radius_),
                        [&](int I) {
                          if (kernels::covers(settings_, v, I, x)) out.push_back(I);
                        });
  std::sort(out.begin(), out.end());
}

Csr MeshfreeSpace::support_lists(const std::vector<Vec2>& points) const {
  const int n = static_cast<int>(points.size());
  Csr csr;
  csr.offset.assign(n + 1, 0);
#pragma omp parallel
  {
    std::vector<int> nb;
#pragma omp for schedule(static)
    for (int p = 0; p < n; ++p) {
      nodes_covering(points[p], nb);
      csr.offset[p + 1] = static_cast<int>(nb.size());
    }
#pragma omp single
    {
      for (int p = 0; p < n; ++p) csr.offset[p + 1] += csr.offset[p];
      csr.index.resize(csr.offset[n]);
    }
#pragma omp for schedule(static)
    for (int p = 0; p < n; ++p) {
      nodes_covering(points[p], nb);
      std::copy(nb.begin(), nb.end(), csr.index.begin() + csr.offset[p]);
    }
  }
  return csr;
}

ShapeTable MeshfreeSpace::shape_table(const std::vector<Vec2>& points, const std::vector<int>& rows,
                                      const Csr& support, bool gradients) const {
  ShapeTable t;
  const int n = static_cast<int>(rows.size());
  t.offset.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) t.offset[k + 1] = t.offset[k] + support.size(rows[k]);
  t.node.resize(t.offset[n]);
  t.phi.resize(t.offset[n]);
  if (gradients) t.dphi.resize(t.offset[n]);
  std::atomic<int> failed{-1};
  const auto v = view();
#pragma omp parallel for schedule(dynamic, 256)
  for (int k = 0; k < n; ++k) {
    const int p = rows[k];
    const int* nb = support.index.data() + support.offset[p];
    const int count = support.size(p);
    std::copy(nb, nb + count, t.node.begin() + t.offset[k]);
    const bool ok =
        kernels::evaluate_shape(settings_, v, points[p], nb, count, t.phi.data() + t.offset[k],
                                gradients ? t.dphi.data() + t.offset[k] : nullptr);
    if (!ok) {
      int expected = -1;
      failed.compare_exchange_strong(expected, p);
    }
  }
  if (failed >= 0) {
    const Vec2& x = points[failed];
    fail("shape functions are undefined at (", x.x(), ", ", x.y(), "): ", support.size(failed),
         " node(s) cover it, too few or in a line for the ", settings_.basis_size(),
         "-term basis; raise discretisation.dilation or refine the nodes there");
  }
  return t;
}

} // namespace mf::implicit
