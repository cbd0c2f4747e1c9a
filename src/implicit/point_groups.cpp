#include "meshfree/implicit/point_groups.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace mf::implicit {

PointGroups::PointGroups(const std::vector<int>& offset, const std::vector<int>& node,
                         const std::vector<Vec2>& x, const std::vector<Vec2>& nodes) {
  const int rows = static_cast<int>(offset.size()) - 1;
  if (rows == 0) return;
  double reach = 0.0;
  Vec2 lo = x[0], hi = x[0];
  for (int r = 0; r < rows; ++r) {
    lo = lo.cwiseMin(x[r]);
    hi = hi.cwiseMax(x[r]);
    for (int k = offset[r]; k < offset[r + 1]; ++k)
      reach = std::max(reach, (nodes[node[k]] - x[r]).norm());
  }
  // Points of same-coloured tiles are at least one tile width apart: more than two reaches.
  const double width = std::max(2.0 * reach * (1.0 + 1e-9), 1e-300);
  const auto cells = [&](double extent) {
    return std::max(1, static_cast<int>(std::floor(extent / width)) + 1);
  };
  const int nx = cells(hi.x() - lo.x()), ny = cells(hi.y() - lo.y());
  const auto tile_of = [&](const Vec2& p) {
    const int ix = std::min(nx - 1, static_cast<int>((p.x() - lo.x()) / width));
    const int iy = std::min(ny - 1, static_cast<int>((p.y() - lo.y()) / width));
    return std::pair<int, int>(ix, iy);
  };
  // Tiles ordered by colour, then row by row; rows by tile, then in table order.
  const auto key = [&](int r) {
    const auto [ix, iy] = tile_of(x[r]);
    const int colour = ix % 2 + 2 * (iy % 2);
    return static_cast<long long>(colour) * nx * ny + static_cast<long long>(iy) * nx + ix;
  };
  std::vector<long long> keys(rows);
  for (int r = 0; r < rows; ++r) keys[r] = key(r);
  row_.resize(rows);
  std::iota(row_.begin(), row_.end(), 0);
  std::stable_sort(row_.begin(), row_.end(), [&](int a, int b) { return keys[a] < keys[b]; });
  const long long per_colour = static_cast<long long>(nx) * ny;
  for (int i = 0; i < rows; ++i) {
    if (i > 0 && keys[row_[i]] == keys[row_[i - 1]]) continue;
    if (i > 0) tile_offset_.push_back(i);
    const int colour = static_cast<int>(keys[row_[i]] / per_colour);
    for (int c = colour + 1; c <= 4; ++c) colour_offset_[c] = tiles() + 1;
  }
  tile_offset_.push_back(rows);
}

bool PointGroups::independent(const ShapeTable& t, int node_count) const {
  for (int c = 0; c < 4; ++c) {
    std::vector<int> tile_of_node(node_count, -1);
    for (int k = colour_offset_[c]; k < colour_offset_[c + 1]; ++k)
      for (int i = tile_offset_[k]; i < tile_offset_[k + 1]; ++i)
        for (int j = t.offset[row_[i]]; j < t.offset[row_[i] + 1]; ++j) {
          int& owner = tile_of_node[t.node[j]];
          if (owner >= 0 && owner != k) return false;
          owner = k;
        }
  }
  return true;
}

int PointGroups::threads() {
  return omp_get_max_threads();
}

} // namespace mf::implicit
