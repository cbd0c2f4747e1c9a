#pragma once
// The discrete function space of a meshfree Galerkin model: the nodes, their supports, the
// shape-function settings, and a search grid to find the nodes that cover a point.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/shape_table.hpp"
#include "meshfree/kernels/shape_functions.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include <vector>

namespace mf::implicit {

/// Compressed rows: row r holds index[offset[r] .. offset[r+1]).
struct Csr {
  std::vector<int> offset{0};
  std::vector<int> index;
  int rows() const { return static_cast<int>(offset.size()) - 1; }
  int size(int r) const { return offset[r + 1] - offset[r]; }
};

class MeshfreeSpace {
public:
  /// `dilation` scales each node's local spacing into its support radius (per direction).
  MeshfreeSpace(geometry::NodeCloud cloud, const kernels::ShapeSettings& settings,
                const Vec2& dilation);

  int node_count() const { return static_cast<int>(cloud_.x.size()); }
  const geometry::NodeCloud& nodes() const { return cloud_; }
  const std::vector<Vec2>& radius() const { return radius_; }
  const kernels::ShapeSettings& settings() const { return settings_; }
  kernels::NodeView view() const { return {cloud_.x.data(), radius_.data(), cloud_.volume.data()}; }

  /// Nodes whose support covers x, in increasing index order.
  void nodes_covering(const Vec2& x, std::vector<int>& out) const;
  /// Support lists of many points (OpenMP-parallel).
  Csr support_lists(const std::vector<Vec2>& points) const;
  /// Shape functions at points[rows[k]] using their support lists; throws mf::Error naming the
  /// first point where the moment matrix is singular.
  ShapeTable shape_table(const std::vector<Vec2>& points, const std::vector<int>& rows,
                         const Csr& support, bool gradients) const;

private:
  /// Nodes whose support radii lie within a factor of 2 of each other, with a cell list sized
  /// for them: a query searches each group only as far as its own largest support, so a
  /// refined region does not make every query scan the reach of the coarsest supports.
  struct RadiusGroup {
    double max_radius = 0.0;
    std::vector<int> node;
    neighbors::PointGrid grid;
  };

  geometry::NodeCloud cloud_;
  std::vector<Vec2> radius_;
  kernels::ShapeSettings settings_;
  std::vector<RadiusGroup> groups_;
};

} // namespace mf::implicit
