#pragma once
// Integration points for meshfree Galerkin: Gauss points on a background grid of cells over the
// body (Belytschko, Lu & Gu 1994; [Faraji 2007] section 2-3), and Gauss points along boundary
// pieces for tractions and penalty constraints.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include <vector>

namespace mf::quadrature {

struct DomainPoints {
  std::vector<Vec2> x;
  std::vector<double> weight; // area weight
  std::vector<int> cell;      // background cell the point came from
  int cell_count = 0;
  // The integration cell of each point: its background cell, or the part of it that node
  // refinement split off (a cell the boundary cuts keeps its subdivisions as one piece); the
  // cells whose mean volumetric strain the B-bar projection takes. Ids below piece_count; an
  // unsplit background cell's piece is its cell's id.
  std::vector<int> piece;
  int piece_count = 0;
};

struct BoundaryPoints {
  std::vector<Vec2> x;
  std::vector<double> weight; // length weight
  std::vector<Vec2> normal;   // outward unit normal
};

/// How fine the integration must be where the nodes are refined: cells (and boundary parts)
/// are at most `ratio` times the local node spacing.
struct CellSizing {
  double spacing = 0.0; // base node spacing
  std::vector<geometry::Refinement> refinement;
  double ratio = 1.0; // cell size / node spacing
  /// Support radius / spacing: the supports of refined nodes reach this many fine spacings
  /// out of their box, and the cells there must resolve them too.
  double reach = 0.0;
  double size_at(const BoundingBox& box) const;
};

/// Background cells of size `cell_size` anchored at the lower-left corner of the body's bounding
/// box, `order` x `order` Gauss points per cell. A cell that overlaps a refinement box is split
/// into four until it is no larger than `sizing` asks; a cell cut by the boundary is split into
/// four `cut_levels` more times, and at the finest level only the points inside the body are kept.
/// With `arcs`, a cell that only a circular hole cuts is integrated on its exact region instead
/// (cell_minus_disc); cells the polygon or two holes cut are still split.
DomainPoints domain_points(const geometry::Domain& domain, double cell_size, int order,
                           int cut_levels, const CellSizing& sizing = {}, bool arcs = false);

/// Gauss points of `order` on each of `pieces` split into parts of length about `part_length`
/// (shorter where `sizing` asks for it).
BoundaryPoints boundary_points(const std::vector<geometry::Curve>& pieces, double part_length,
                               int order, const CellSizing& sizing = {});

} // namespace mf::quadrature
