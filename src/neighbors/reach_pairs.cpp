#include "meshfree/neighbors/reach_pairs.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/parallel_rows.hpp"
#include <algorithm>
#include <cmath>

namespace mf::neighbors {

namespace {
/// The points of one radius class binned into cubes: members sorted by cell (ascending index
/// within a cell), with their coordinates and radii copied in that order so that a query streams
/// contiguous memory.
struct ClassGrid {
  double lo[3] = {0.0, 0.0, 0.0};
  double cell = 1.0;
  long dims[3] = {1, 1, 1};
  double radius_max = 0.0;
  std::vector<long> start; // CSR offsets per cell
  std::vector<int> index;  // the point of each sorted slot
  std::vector<double> x, radius;

  long coord(double v, int d) const {
    const double c = std::floor((v - lo[d]) / cell);
    if (!(c > 0.0)) return 0; // also NaN
    return c >= static_cast<double>(dims[d] - 1) ? dims[d] - 1 : static_cast<long>(c);
  }
};

ClassGrid bin_class(const std::vector<double>& x, const std::vector<double>& radius,
                    const std::vector<int>& members, double scale) {
  ClassGrid g;
  const int count = static_cast<int>(members.size());
  for (int d = 0; d < 3; ++d) g.lo[d] = x[3 * members[0] + d];
  double hi[3] = {g.lo[0], g.lo[1], g.lo[2]};
  for (const int i : members) {
    g.radius_max = std::max(g.radius_max, radius[i]);
    for (int d = 0; d < 3; ++d) {
      g.lo[d] = std::min(g.lo[d], x[3 * i + d]);
      hi[d] = std::max(hi[d], x[3 * i + d]);
    }
  }
  // Cells of the class' largest pair reach, so a pair within the class lies in adjacent cells;
  // doubled while the class' box would need more than about 4 cells per point (a sparse class
  // spread over a large body).
  g.cell = 2.0 * g.radius_max * scale;
  const auto cells = [&] {
    double total = 1.0;
    for (int d = 0; d < 3; ++d) total *= std::floor((hi[d] - g.lo[d]) / g.cell) + 1.0;
    return total;
  };
  while (cells() > 4.0 * count + 64.0) g.cell *= 2.0;
  for (int d = 0; d < 3; ++d)
    g.dims[d] = static_cast<long>(std::floor((hi[d] - g.lo[d]) / g.cell)) + 1;
  // Counting sort by cell; members are ascending, so each cell's points stay ascending.
  g.start.assign(g.dims[0] * g.dims[1] * g.dims[2] + 1, 0);
  std::vector<long> cell_of(count);
  for (int k = 0; k < count; ++k) {
    const int i = members[k];
    cell_of[k] = (g.coord(x[3 * i + 2], 2) * g.dims[1] + g.coord(x[3 * i + 1], 1)) * g.dims[0] +
                 g.coord(x[3 * i], 0);
    ++g.start[cell_of[k] + 1];
  }
  for (std::size_t c = 1; c < g.start.size(); ++c) g.start[c] += g.start[c - 1];
  g.index.resize(count);
  g.x.resize(3 * static_cast<std::size_t>(count));
  g.radius.resize(count);
  std::vector<long> fill(g.start.begin(), g.start.end() - 1);
  for (int k = 0; k < count; ++k) {
    const long slot = fill[cell_of[k]]++;
    const int i = members[k];
    g.index[slot] = i;
    g.radius[slot] = radius[i];
    for (int d = 0; d < 3; ++d) g.x[3 * slot + d] = x[3 * i + d];
  }
  return g;
}

/// Sorts a short, nearly sorted row (cells are visited in the order the points were generated
/// in, so runs arrive ascending): insertion sort, linear in the row plus its inversions.
void sort_row(std::vector<int>& row) {
  for (std::size_t a = 1; a < row.size(); ++a) {
    const int v = row[a];
    std::size_t b = a;
    for (; b > 0 && row[b - 1] > v; --b) row[b] = row[b - 1];
    row[b] = v;
  }
}

} // namespace

PairList pairs_within_reach(const std::vector<double>& x, const std::vector<double>& radius,
                            double scale, int rows) {
  const int n = static_cast<int>(x.size() / 3);
  MF_REQUIRE(scale > 0.0, "pairs_within_reach: the scale must be positive, got ", scale);
  MF_REQUIRE(static_cast<int>(radius.size()) == n, "pairs_within_reach: ", radius.size(),
             " radii for ", n, " points");
  MF_REQUIRE(rows >= 0 && rows <= n, "pairs_within_reach: ", rows, " rows of ", n, " points");
  PairList out;
  if (rows == 0) return out;
  const double r_min = *std::min_element(radius.begin(), radius.end());
  MF_REQUIRE(r_min > 0.0 && std::isfinite(*std::max_element(radius.begin(), radius.end())),
             "pairs_within_reach: every radius must be positive and finite");
  // Class c holds the radii in [r_min 2^c, r_min 2^(c+1)).
  std::vector<std::vector<int>> members;
  for (int i = 0; i < n; ++i) {
    int e = 0;
    std::frexp(radius[i] / r_min, &e); // radius / r_min = m 2^e, m in [0.5, 1)
    const std::size_t c = static_cast<std::size_t>(std::clamp(e - 1, 0, 60));
    if (members.size() <= c) members.resize(c + 1);
    members[c].push_back(i);
  }
  std::vector<ClassGrid> grids;
  for (const std::vector<int>& m : members)
    if (!m.empty()) grids.push_back(bin_class(x, radius, m, scale));

  parallel_rows(
      rows,
      [&](int i, std::vector<int>& row) {
        const double xi[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
        for (const ClassGrid& g : grids) {
          // Every partner in the class lies within w = (r_i + r_max) scale of x_i along each
          // axis; the 1e-9 margin covers the rounding of the cell coordinates and of r2.
          const double w = (radius[i] + g.radius_max) * scale * (1.0 + 1e-9);
          long a0[3], a1[3];
          for (int d = 0; d < 3; ++d) {
            a0[d] = g.coord(xi[d] - w, d);
            a1[d] = g.coord(xi[d] + w, d);
          }
          for (long cz = a0[2]; cz <= a1[2]; ++cz)
            for (long cy = a0[1]; cy <= a1[1]; ++cy) {
              const long row_start = (cz * g.dims[1] + cy) * g.dims[0];
              // Cells a0[0] .. a1[0] of one row are contiguous in the sorted order.
              const long k0 = g.start[row_start + a0[0]], k1 = g.start[row_start + a1[0] + 1];
              for (long k = k0; k < k1; ++k) {
                const double* xj = &g.x[3 * k];
                double r2 = 0.0;
                for (int d = 0; d < 3; ++d) {
                  const double dx = xi[d] - xj[d];
                  r2 += dx * dx;
                }
                const double reach = (radius[i] + g.radius[k]) * scale;
                if (r2 < reach * reach && g.index[k] != i) row.push_back(g.index[k]);
              }
            }
        }
        sort_row(row);
      },
      out.offset, out.partner);
  return out;
}

} // namespace mf::neighbors
