#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/parallel_rows.hpp"
#include "meshfree/implicit/shape_tabulation.hpp"
#include <algorithm>
#include <cmath>

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

void MeshfreeSpace::hide_behind_holes(const geometry::Domain& body) {
  holes_ = body.outline_holes();
  hole_box_.clear();
  for (const geometry::OutlineHole& h : holes_) hole_box_.push_back(h.bounds());
}

bool MeshfreeSpace::hidden(const Vec2& x, int I, const std::vector<int>& near) const {
  const Vec2& y = cloud_.x[I];
  const double tol = 1e-9 * radius_[I].maxCoeff();
  for (int h : near) {
    if (holes_[h].contains(0.5 * (x + y), tol)) return true; // a face's point to the other face
    for (const geometry::Curve& c : holes_[h].loop())
      if (c.crossed_by(x, y, tol)) return true;
  }
  return false;
}

void MeshfreeSpace::nodes_covering(const Vec2& x, std::vector<int>& out) const {
  out.clear();
  const auto v = view();
  // The holes within the largest support's reach of x: the only ones that can hide a node that
  // covers x (none, for most points).
  thread_local std::vector<int> near; // kept between calls: no allocation
  near.clear();
  const double reach = groups_.empty() ? 0.0 : groups_.front().max_radius;
  for (std::size_t h = 0; h < holes_.size(); ++h)
    if (hole_box_[h].contains(x, reach)) near.push_back(static_cast<int>(h));
  for (const RadiusGroup& g : groups_) {
    const Vec2 reach(g.max_radius, g.max_radius);
    g.grid.for_each_in_box(x - reach, x + reach, [&](int k) {
      const int I = g.node[k];
      if (kernels::covers(settings_, v, I, x) && !(!near.empty() && hidden(x, I, near)))
        out.push_back(I);
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
  const auto v = view();
  int failed = -1;
  ShapeTable t = tabulate_shapes<ShapeTable>(
      rows, support, gradients, 2.0 * node_count(), node_count(),
      [&](int p, const int* nb, int count, double* phi, Vec2* dphi) {
        return kernels::evaluate_shape(settings_, v, points[p], nb, count, phi, dphi);
      },
      failed);
  if (failed >= 0) {
    const Vec2& x = points[failed];
    fail("shape functions are undefined at (", x.x(), ", ", x.y(), "): ", support.size(failed),
         " node(s) cover it, too few or in a line for the ", settings_.basis_size(),
         "-term basis; raise discretisation.dilation or refine the nodes there");
  }
  return t;
}

} // namespace mf::implicit
