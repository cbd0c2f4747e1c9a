#pragma once
// Finds the tetrahedron of a mesh that holds a physical point, and the point's natural
// coordinates in it: for sampling a solution at gauges or at the particles of a later stage.
#include "meshfree/core/types.hpp"
#include "meshfree/fem/tetrahedra.hpp"
#include <vector>

namespace mf::fem {

/// A uniform grid of cells about the mean element's size, each listing the elements whose box
/// overlaps it (a 10-node element's box holds its edges' Bezier control points, 2 m - (a + b) / 2,
/// so a curved element lies inside it). A query examines the elements of the point's cell: the
/// straight-sided map is inverted directly, a curved one by Newton's method from there. Points
/// within 1e-9 (natural coordinates) of an element count as inside it, so points on faces are
/// found. Keeps a pointer to the mesh, which must outlive the locator and not change.
class TetLocator {
public:
  explicit TetLocator(const TetMesh& mesh);
  /// False if no element holds x (element and xi are then unchanged).
  bool locate(const Vec3& x, int& element, Vec3& xi) const;

private:
  int cell_of(const Vec3& x) const;
  /// The natural coordinates of x in element e; false where Newton's method fails.
  bool natural(int e, const Vec3& x, Vec3& xi) const;

  const TetMesh* mesh_;
  std::vector<Vec3> lo_, hi_; // each element's box
  Vec3 origin_{0.0, 0.0, 0.0};
  double cell_ = 1.0;
  int dims_[3] = {1, 1, 1};
  std::vector<int> start_, element_; // the elements of each cell, in CSR
};

} // namespace mf::fem
