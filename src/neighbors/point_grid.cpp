#include "meshfree/neighbors/point_grid.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>

namespace mf::neighbors {

PointGrid::PointGrid(const std::vector<Vec2>& points, double cell_size) : original_(points) {
  MF_REQUIRE(cell_size > 0.0, "PointGrid: cell size must be positive, got ", cell_size);
  if (points.empty()) return;
  Vec2 lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Bound the number of cells so that a huge radius on a small cloud stays cheap, and a tiny
  // radius on a big cloud does not allocate more cells than about 4 per point.
  const double max_cells = 4.0 * static_cast<double>(points.size()) + 16.0;
  const Vec2 extent = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300));
  cell_ = cell_size;
  while ((extent.x() / cell_ + 1.0) * (extent.y() / cell_ + 1.0) > max_cells) cell_ *= 2.0;
  origin_ = lo;
  nx_ = static_cast<int>(std::floor(extent.x() / cell_)) + 1;
  ny_ = static_cast<int>(std::floor(extent.y() / cell_)) + 1;

  std::vector<int> cell_of(points.size());
  start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    cell_of[i] = cell_y(points[i].y()) * nx_ + cell_x(points[i].x());
    ++start_[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  points_.resize(points.size());
  index_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int k = fill[cell_of[i]]++;
    points_[k] = points[i];
    index_[k] = static_cast<int>(i);
  }
}

} // namespace mf::neighbors
