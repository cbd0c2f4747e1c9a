#include "meshfree/neighbors/pair_list.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/parallel_rows.hpp"
#include <algorithm>
#include <cmath>

namespace mf::neighbors {

PairList pairs_within(const std::vector<double>& x, double radius) {
  MF_REQUIRE(radius > 0.0, "pairs_within: the radius must be positive, got ", radius);
  const int n = static_cast<int>(x.size() / 3);
  PairList out;
  if (n == 0) return out;
  double lo[3] = {x[0], x[1], x[2]}, hi[3] = {x[0], x[1], x[2]};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], x[3 * i + d]);
      hi[d] = std::max(hi[d], x[3 * i + d]);
    }
  long dims[3];
  for (int d = 0; d < 3; ++d)
    dims[d] = std::max(1L, static_cast<long>(std::floor((hi[d] - lo[d]) / radius)) + 1);
  const auto cell_coord = [&](int i, int d) {
    return std::min(dims[d] - 1, static_cast<long>(std::floor((x[3 * i + d] - lo[d]) / radius)));
  };
  const long cells = dims[0] * dims[1] * dims[2];
  MF_REQUIRE(cells < 4L * n + 1000000L, "pairs_within: the cloud spans ", cells,
             " cells of the search radius ", radius, "; is the radius far too small?");
  // Counting sort of the points by cell.
  std::vector<long> start(cells + 1, 0);
  std::vector<long> cell_of(n);
  for (int i = 0; i < n; ++i) {
    cell_of[i] = (cell_coord(i, 2) * dims[1] + cell_coord(i, 1)) * dims[0] + cell_coord(i, 0);
    ++start[cell_of[i] + 1];
  }
  for (long c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<int> sorted(n);
  {
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i) sorted[fill[cell_of[i]]++] = i;
  }
  const double r2 = radius * radius;
  parallel_rows(
      n,
      [&](int i, std::vector<int>& row) {
        const long ci[3] = {cell_coord(i, 0), cell_coord(i, 1), cell_coord(i, 2)};
        for (long cz = std::max(0L, ci[2] - 1); cz <= std::min(dims[2] - 1, ci[2] + 1); ++cz)
          for (long cy = std::max(0L, ci[1] - 1); cy <= std::min(dims[1] - 1, ci[1] + 1); ++cy)
            for (long cx = std::max(0L, ci[0] - 1); cx <= std::min(dims[0] - 1, ci[0] + 1); ++cx) {
              const long c = (cz * dims[1] + cy) * dims[0] + cx;
              for (long k = start[c]; k < start[c + 1]; ++k) {
                const int j = sorted[k];
                if (j == i) continue;
                const double dx = x[3 * j] - x[3 * i], dy = x[3 * j + 1] - x[3 * i + 1],
                             dz = x[3 * j + 2] - x[3 * i + 2];
                if (dx * dx + dy * dy + dz * dz <= r2) row.push_back(j);
              }
            }
        std::sort(row.begin(), row.end());
      },
      out.offset, out.partner);
  return out;
}

} // namespace mf::neighbors
