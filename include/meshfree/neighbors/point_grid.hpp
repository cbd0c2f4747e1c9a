#pragma once
// Uniform cell-linked list over 2D points (Hockney & Eastwood's cell list): building is O(N),
// a query visits only the cells that overlap its box. Points are stored sorted by cell so a
// query walks contiguous memory.
#include "meshfree/core/types.hpp"
#include <vector>

namespace mf::neighbors {

class PointGrid {
public:
  PointGrid() = default;
  /// `cell_size` should be about the largest query radius.
  PointGrid(const std::vector<Vec2>& points, double cell_size);

  /// Calls f(index) for every point inside the closed box [lo, hi].
  template <class F> void for_each_in_box(const Vec2& lo, const Vec2& hi, F&& f) const {
    if (points_.empty()) return;
    const int i0 = cell_x(lo.x()), i1 = cell_x(hi.x());
    const int j0 = cell_y(lo.y()), j1 = cell_y(hi.y());
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const int c = j * nx_ + i;
        for (int k = start_[c]; k < start_[c + 1]; ++k) {
          const Vec2& p = points_[k];
          if (p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y())
            f(index_[k]);
        }
      }
  }

  /// Calls f(index) for every point with |p - x| <= r.
  template <class F> void for_each_within(const Vec2& x, double r, F&& f) const {
    const double r2 = r * r;
    for_each_in_box(x - Vec2(r, r), x + Vec2(r, r), [&](int i) {
      if ((original_[i] - x).squaredNorm() <= r2) f(i);
    });
  }

  std::size_t size() const { return points_.size(); }

private:
  int cell_x(double x) const {
    return clamp_index(static_cast<int>((x - origin_.x()) / cell_), nx_);
  }
  int cell_y(double y) const {
    return clamp_index(static_cast<int>((y - origin_.y()) / cell_), ny_);
  }
  static int clamp_index(int i, int n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); }

  Vec2 origin_{0.0, 0.0};
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> start_;   // CSR offsets per cell
  std::vector<Vec2> points_; // points sorted by cell
  std::vector<int> index_;   // original index of each sorted point
  std::vector<Vec2> original_;
};

} // namespace mf::neighbors
