#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/parallel_rows.hpp"
#include "meshfree/core/progress.hpp"
#include <algorithm>
#include <atomic>
#include <cmath>
#include <omp.h>

namespace mf::implicit {

MeshfreeSpace::MeshfreeSpace(geometry::NodeCloud cloud, const kernels::ShapeSettings& settings,
                             const Vec2& dilation)
    : cloud_(std::move(cloud)), settings_(settings) {
  MF_REQUIRE(!cloud_.x.empty(), "the discretisation has no nodes");
  radius_.resize(cloud_.x.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < cloud_.x.size(); ++i) {
    radius_[i] = cloud_.spacing[i] * dilation;
    largest = std::max(largest, radius_[i].maxCoeff());
  }
  std::vector<int> group_of(cloud_.x.size());
  int groups = 1;
  for (std::size_t i = 0; i < cloud_.x.size(); ++i) {
    group_of[i] =
        std::min(30, static_cast<int>(std::floor(std::log2(largest / radius_[i].maxCoeff()))));
    groups = std::max(groups, group_of[i] + 1);
  }
  std::vector<RadiusGroup> all(groups);
  for (std::size_t i = 0; i < cloud_.x.size(); ++i) {
    RadiusGroup& g = all[group_of[i]];
    g.node.push_back(static_cast<int>(i));
    g.max_radius = std::max(g.max_radius, radius_[i].maxCoeff());
  }
  for (RadiusGroup& g : all) {
    if (g.node.empty()) continue;
    std::vector<Vec2> x;
    for (int i : g.node) x.push_back(cloud_.x[i]);
    g.grid = neighbors::PointGrid(x, g.max_radius);
    groups_.push_back(std::move(g));
  }
}

void MeshfreeSpace::nodes_covering(const Vec2& x, std::vector<int>& out) const {
  out.clear();
  const auto v = view();
  for (const RadiusGroup& g : groups_) {
    const Vec2 reach(g.max_radius, g.max_radius);
    g.grid.for_each_in_box(x - reach, x + reach, [&](int k) {
      const int I = g.node[k];
      if (kernels::covers(settings_, v, I, x)) out.push_back(I);
    });
  }
  std::sort(out.begin(), out.end());
}

Csr MeshfreeSpace::support_lists(const std::vector<Vec2>& points) const {
  Csr csr;
  parallel_rows(
      static_cast<int>(points.size()),
      [&](int p, std::vector<int>& row) { nodes_covering(points[p], row); }, csr.offset, csr.index);
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
  // Progress of large systems: the points done, counted by all threads, reported by thread 0;
  // only for tables of more points than nodes (the body's integration points), not for the few
  // boundary points nor for samples at the nodes.
  const bool report = 2.0 * node_count() >= log::kProgressUnknowns && n > node_count();
  log::PhaseProgress progress("shape functions", n, report);
#pragma omp parallel for schedule(dynamic, 256)
  for (int k = 0; k < n; ++k) {
    progress.count_one(omp_get_thread_num());
    const int p = rows[k];
    const int* nb = support.index.data() + support.offset[p];
    const int count = support.size(p);
    std::copy(nb, nb + count, t.node.begin() + t.offset[k]);
    const bool ok =
        kernels::evaluate_shape(settings_, v, points[p], nb, count, t.phi.data() + t.offset[k],
                                gradients ? t.dphi.data() + t.offset[k] : nullptr);
    if (!ok) { // keep the lowest failing point, so the message does not depend on threads
      int seen = failed.load();
      while ((seen < 0 || p < seen) && !failed.compare_exchange_weak(seen, p)) {
      }
    }
  }
  progress.finish();
  if (failed >= 0) {
    const Vec2& x = points[failed];
    fail("shape functions are undefined at (", x.x(), ", ", x.y(), "): ", support.size(failed),
         " node(s) cover it, too few or in a line for the ", settings_.basis_size(),
         "-term basis; raise discretisation.dilation or refine the nodes there");
  }
  return t;
}

} // namespace mf::implicit
