#pragma once
// Integration points in groups that threads can assemble at once without sharing a matrix or
// vector entry, in an order that does not depend on the number of threads.
#include "meshfree/core/types.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include <omp.h>
#include <vector>

namespace mf::implicit {

/// The points of a shape table sorted into square tiles wider than twice the farthest reach
/// from a point to a node of its support, the tiles coloured as a 2 x 2 checkerboard: two points
/// in different tiles of one colour lie more than two reaches apart, so they share no node.
/// for_each runs the colours one after another, the tiles of a colour in parallel (OpenMP), and
/// the points of a tile in table order; so every entry receives its additions in one order, the
/// same on any number of threads, and results do not change with the thread count.
class PointGroups {
public:
  PointGroups() = default;
  /// `x`: the position of each table row; `nodes`: the positions of the nodes it names.
  PointGroups(const ShapeTable& t, const std::vector<Vec2>& x, const std::vector<Vec2>& nodes)
      : PointGroups(t.offset, t.node, x, nodes) {}
  /// The same for a table given by its compressed rows of nodes; a 3D table passes the x-y of
  /// its points and nodes: tiles are then columns along z, whose points one thread takes.
  PointGroups(const std::vector<int>& offset, const std::vector<int>& node,
              const std::vector<Vec2>& x, const std::vector<Vec2>& nodes);

  /// Calls work(row, thread) for every row of the table, thread in [0, threads()).
  template <class Work> void for_each(Work&& work) const;
  /// The most threads for_each uses (OpenMP's maximum).
  static int threads();
  int tiles() const { return static_cast<int>(tile_offset_.size()) - 1; }
  /// The number of table rows grouped (for_each visits each once).
  int rows() const { return static_cast<int>(row_.size()); }
  /// True when no node of `t` (node_count of them) belongs to points of two tiles of one colour:
  /// the property that makes for_each safe.
  bool independent(const ShapeTable& t, int node_count) const;

private:
  std::vector<int> colour_offset_{0, 0, 0, 0, 0}; // tiles of colour c: [colour_offset_[c], [c+1])
  std::vector<int> tile_offset_{0};               // rows of tile k: row_[tile_offset_[k] ...]
  std::vector<int> row_;
};

template <class Work> void PointGroups::for_each(Work&& work) const {
  for (int c = 0; c < 4; ++c) {
    const int first = colour_offset_[c], last = colour_offset_[c + 1];
#pragma omp parallel for schedule(dynamic, 1)
    for (int k = first; k < last; ++k) {
      const int thread = omp_get_thread_num();
      for (int i = tile_offset_[k]; i < tile_offset_[k + 1]; ++i) work(row_[i], thread);
    }
  }
}

} // namespace mf::implicit
