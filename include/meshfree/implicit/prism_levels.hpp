#pragma once
// Levels along z of a prism's nodes and integration cells. The base levels split the depth into
// round(depth / spacing) equal layers. A refinement box given in the plane refines the section
// through the whole depth on the base layers (where the field does not vary along z, as about a
// bore, extra layers only cost). A box given in 3D refines along z as in the section: over its
// z range, widened to the base levels around it, it has equal layers of its own at its spacing.
// The section's node cloud at a level is made with the boxes that refine it there, and a node
// stands only on the levels of spacings no finer than its own: a coarse node on the base
// levels, a node of a 3D box on that box's too. So a 3D box's region is refined in all three
// directions while the rest of the section keeps the base layers, and its nodes' supports reach
// their own layers, not the base's.
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/geometry/prism.hpp"
#include <vector>

namespace mf::implicit {

/// A level along z: origin + index * step, kept in that form so that equal layers put their
/// points where a single loop over them would.
struct Level {
  double origin = 0.0, step = 0.0;
  int index = 0;
  double z() const { return origin + index * step; }
};

/// Equal layers over a range along z, made for nodes `spacing` apart.
struct Levels {
  double spacing = 0.0;
  std::vector<Level> at;
  /// True when z lies in the range of the levels (to `tol`).
  bool spans(double z, double tol) const {
    return !at.empty() && z >= at.front().z() - tol && z <= at.back().z() + tol;
  }
  /// The layer thicknesses below and above level k (0 past either end).
  double below(std::size_t k) const { return k == 0 ? 0.0 : at[k].z() - at[k - 1].z(); }
  double above(std::size_t k) const { return k + 1 == at.size() ? 0.0 : at[k + 1].z() - at[k].z(); }
};

/// The base levels for `spacing` (first), then those of each refinement box in order, at its
/// spacing times `scale` (1 for nodes, cell_size / spacing for cells); each box's z range is
/// first widened by `reach` times its spacing (the reach of its nodes' supports, which its
/// cells must resolve; 0 for nodes). A box given in the plane, or whose range misses the body,
/// has no levels.
std::vector<Levels> prism_levels(const geometry::Prism& body, double spacing,
                                 const std::vector<geometry::Refinement>& refinement, double scale,
                                 double reach);

/// A height where levels of one or more grids meet (to `tol`): each grid's index of its level
/// there, -1 for a grid with none; `z` is the last such grid's.
struct MergedLevel {
  double z = 0.0;
  std::vector<int> index;
};
std::vector<MergedLevel> merged_levels(const std::vector<Levels>& grids, double tol);

/// A slab between two consecutive levels of all the grids merged, with the refinement boxes
/// that refine it: those given in the plane, and those given in 3D whose (widened) range holds
/// it.
struct Slab {
  Level lo;               // its lower level; its upper is lo with index + 1
  std::vector<int> boxes; // indices of the refinement boxes that refine it
  double thickness() const { return lo.step; }
  /// The height at t in [0, 1] across the slab.
  double z(double t) const { return lo.origin + (lo.index + t) * lo.step; }
};

/// The refinement boxes of `boxes`.
std::vector<geometry::Refinement> boxes_of(const std::vector<int>& boxes,
                                           const std::vector<geometry::Refinement>& refinement);

/// The slabs of the body from its z0 to its z1 for cells of `cell_size`, nodes `spacing` apart
/// and supports of `reach` spacings (quadrature::CellSizing).
std::vector<Slab> prism_slabs(const geometry::Prism& body, double spacing, double cell_size,
                              const std::vector<geometry::Refinement>& refinement, double reach);

} // namespace mf::implicit
