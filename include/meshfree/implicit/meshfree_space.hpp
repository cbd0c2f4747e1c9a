#pragma once
// The discrete function space of a meshfree Galerkin model: the nodes, their supports, the
// shape-function settings, and a search grid to find the nodes that cover a point.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
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

  /// From now on a node does not cover a point that one of `body`'s holes of an outline (a
  /// polygon, a slot, a loop: a notch or a slit) hides from it: the segment between them
  /// crosses the hole's outline, or its middle lies in the hole. The visibility criterion of
  /// [Belytschko, Lu & Gu 1994] (docs/references.md), kept to such holes: along a circular hole's
  /// wall or the outline's concave arcs it would hide neighbours from each other and leave
  /// points with too few nodes.
  void hide_behind_holes(const geometry::Domain& body);
  /// Nodes whose support covers x (and that see it, where hide_behind_holes asked), in
  /// increasing index order.
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

  /// True where one of the holes `near` (indices into holes_) hides node I from x.
  bool hidden(const Vec2& x, int I, const std::vector<int>& near) const;

  geometry::NodeCloud cloud_;
  std::vector<Vec2> radius_;
  std::vector<geometry::OutlineHole> holes_; // that hide nodes (hide_behind_holes)
  std::vector<BoundingBox> hole_box_;
  kernels::ShapeSettings settings_;
  std::vector<RadiusGroup> groups_;
};

} // namespace mf::implicit
