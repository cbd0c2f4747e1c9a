#pragma once
// Node clouds for meshfree Galerkin: a regular lattice inside the body, nodes along every
// boundary piece, and optional boxes of finer spacing (local refinement).
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include <vector>

namespace mf::geometry {

struct Refinement {
  BoundingBox box;
  double spacing = 0.0;
  // In a prism (implicit/prism_levels): a box given in 3D refines along z too, over its range
  // [z_lo, z_hi]; one given in the plane refines the section through the whole depth.
  bool along_z = false;
  double z_lo = -1e300, z_hi = 1e300;
};

struct NodeCloud {
  std::vector<Vec2> x;         // positions
  std::vector<double> spacing; // local nominal spacing at each node
  std::vector<double> volume;  // nodal volume (area) used by the RK construction
};

/// Generates nodes with spacing `spacing`, finer inside each refinement box. Nodes are sorted
/// in horizontal strips (row-major by lattice cell) so that contiguous ranges are compact in
/// space, which keeps the matrix bandwidth and the MPI partition boundaries small.
NodeCloud generate_nodes(const Domain& domain, double spacing,
                         const std::vector<Refinement>& refinements);

/// Each node's spacing raised to the largest spacing of a coarser node within that node's own
/// spacing of it: a node on a finer box's border then reaches as far as its coarser neighbours,
/// so that a coarser column between two finer boxes, or between a finer box and the boundary,
/// is not the only one that covers the points beside it. The supports of adapted clouds
/// (discretisation.adapt), whose boxes lie anywhere, are made from it.
void grade_spacing(NodeCloud& cloud);

/// A boundary piece cut where it enters or leaves a refinement box, so that each part has one
/// local spacing.
std::vector<Curve> split_at_refinements(const Curve& c, const std::vector<Refinement>& refinements);

/// Local spacing at p: the finest refinement box that contains p, else the base spacing.
double local_spacing(const Vec2& p, double spacing, const std::vector<Refinement>& refinements);

} // namespace mf::geometry
