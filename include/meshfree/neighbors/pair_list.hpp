#pragma once
// All pairs of points closer than a radius, found with a uniform cell list (Hockney & Eastwood):
// points are binned into cubes of the radius' size and each point examines the 27 (9 in a plane)
// cubes around its own, so building is O(N) for a uniform cloud.
#include <vector>

namespace mf::neighbors {

/// Compressed rows: row i holds partner[offset[i] .. offset[i+1]), sorted increasingly.
struct PairList {
  std::vector<long> offset{0};
  std::vector<int> partner;
  int rows() const { return static_cast<int>(offset.size()) - 1; }
  /// Whole: offsets from 0 to the partners' count that never go down, partners that name rows
  /// (a list read back from a checkpoint is checked so before it is used).
  bool consistent() const {
    if (offset.empty() || offset.front() != 0 ||
        offset.back() != static_cast<long>(partner.size()))
      return false;
    for (std::size_t i = 1; i < offset.size(); ++i)
      if (offset[i] < offset[i - 1]) return false;
    for (const int j : partner)
      if (j < 0 || j >= rows()) return false;
    return true;
  }
};

/// Every j != i with |x_j - x_i|^2 <= radius^2, for points given as x[3i .. 3i+2] (z = 0 for
/// points in a plane). Each pair appears in both rows. OpenMP-parallel over points.
PairList pairs_within(const std::vector<double>& x, double radius);

} // namespace mf::neighbors
