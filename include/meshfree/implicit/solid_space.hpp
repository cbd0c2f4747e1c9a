#pragma once
// The function space of a 3D meshfree body: the nodes, their spherical (or box) supports, the
// reproducing-kernel settings, and a cell grid to find the nodes whose supports cover a point.
#include "meshfree/core/types.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/kernels/shape_functions_3d.hpp"
#include <vector>

namespace mf::implicit {

class SolidSpace {
public:
  /// `dilation` scales each node's local spacing into its support radius.
  SolidSpace(SolidNodes nodes, const kernels::ShapeSettings& settings, double dilation);

  int node_count() const { return static_cast<int>(nodes_.x.size()); }
  const SolidNodes& nodes() const { return nodes_; }
  kernels::NodeView3 view() const {
    return {nodes_.x.data(), radius_.data(), nodes_.volume.data()};
  }

  /// Nodes whose support covers x, in increasing index order.
  void nodes_covering(const Vec3& x, std::vector<int>& out) const;
  /// Support lists of many points (threaded).
  Csr support_lists(const std::vector<Vec3>& points) const;
  /// Shape functions at points[rows[k]]; throws mf::Error naming the first point where the
  /// moment matrix is singular.
  SolidShapeTable shape_table(const std::vector<Vec3>& points, const std::vector<int>& rows,
                              const Csr& support, bool gradients) const;

private:
  int cell_of(const Eigen::Vector3i& c) const {
    return (c.z() * dims_.y() + c.y()) * dims_.x() + c.x();
  }
  Eigen::Vector3i cell_at(const Vec3& x) const;

  SolidNodes nodes_;
  std::vector<Vec3> radius_;
  kernels::ShapeSettings settings_;
  double reach_ = 0.0; // the largest support radius: the grid's cell size
  Vec3 origin_{0.0, 0.0, 0.0};
  Eigen::Vector3i dims_{1, 1, 1};
  std::vector<int> cell_start_, cell_node_; // nodes by cell, compressed
};

} // namespace mf::implicit
