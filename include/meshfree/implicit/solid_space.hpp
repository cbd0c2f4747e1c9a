#pragma once
// The function space of a 3D meshfree body: the nodes, their spherical (or box) supports, the
// reproducing-kernel settings, and a cell grid to find the nodes whose supports cover a point.
#include "meshfree/core/types.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/kernels/shape_functions_3d.hpp"
#include <vector>

namespace mf::implicit {

/// Shape functions and gradients at a list of points, in compressed rows.
struct SolidShapeTable {
  std::vector<int> offset{0};
  std::vector<int> node;
  std::vector<double> phi;
  std::vector<Vec3> dphi;
  /// The test functions' gradients where they differ from the trial ones (the variationally
  /// consistent correction); empty otherwise.
  std::vector<Vec3> test_dphi;
  /// With the volumetric strain of a cell's mean (implicit/volumetric_projection): each entry's
  /// cell mean of the gradient less its own, for the trial and (where they differ) the test
  /// functions; empty otherwise. The strain matrix becomes B + m (mean g - g)^T / 3, m = [1 1 1 0
  /// 0 0].
  std::vector<Vec3> volumetric_shift, test_volumetric_shift;
  int rows() const { return static_cast<int>(offset.size()) - 1; }
  const Vec3* test_gradients(int r) const {
    return (test_dphi.empty() ? dphi.data() : test_dphi.data()) + offset[r];
  }
  /// The shifts of row r (null without the projection).
  const Vec3* trial_shifts(int r) const {
    return volumetric_shift.empty() ? nullptr : volumetric_shift.data() + offset[r];
  }
  const Vec3* test_shifts(int r) const {
    if (volumetric_shift.empty()) return nullptr;
    return (test_volumetric_shift.empty() ? volumetric_shift.data()
                                          : test_volumetric_shift.data()) +
           offset[r];
  }
};

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
