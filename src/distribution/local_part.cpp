#include "meshfree/distribution/local_part.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>

namespace mf::distribution {

namespace {

/// Marks every particle within `reach` of an owned one: a cell list of the whole body with cells
/// of side `reach`, each owned particle examining the 27 cells around its own.
std::vector<long> ghost_ids(const particles::ParticleSet& whole, long first, long end,
                            double reach) {
  const int n = whole.size();
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = whole.X[d];
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], whole.X[3 * i + d]);
      hi[d] = std::max(hi[d], whole.X[3 * i + d]);
    }
  long cells[3];
  for (int d = 0; d < 3; ++d)
    cells[d] = std::max(1L, static_cast<long>(std::floor((hi[d] - lo[d]) / reach)) + 1);
  const auto cell_of = [&](int i, int d) {
    return std::min(cells[d] - 1, static_cast<long>((whole.X[3 * i + d] - lo[d]) / reach));
  };
  const auto key = [&](long a, long b, long c) { return (c * cells[1] + b) * cells[0] + a; };
  std::vector<std::pair<long, int>> sorted(n);
  for (int i = 0; i < n; ++i) sorted[i] = {key(cell_of(i, 0), cell_of(i, 1), cell_of(i, 2)), i};
  std::sort(sorted.begin(), sorted.end());
  const double r2 = reach * reach * (1.0 + 1e-12);
  std::vector<char> mark(n, 0);
  for (long i = first; i < end; ++i) {
    const long c[3] = {cell_of(i, 0), cell_of(i, 1), cell_of(i, 2)};
    for (long dc = -1; dc <= 1; ++dc)
      for (long db = -1; db <= 1; ++db)
        for (long da = -1; da <= 1; ++da) {
          const long a = c[0] + da, b = c[1] + db, z = c[2] + dc;
          if (a < 0 || b < 0 || z < 0 || a >= cells[0] || b >= cells[1] || z >= cells[2]) continue;
          const long k = key(a, b, z);
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(k, -1));
          for (; it != sorted.end() && it->first == k; ++it) {
            const int j = it->second;
            if ((j >= first && j < end) || mark[j]) continue;
            double d2 = 0.0;
            for (int d = 0; d < 3; ++d) {
              const double e = whole.X[3 * j + d] - whole.X[3 * i + d];
              d2 += e * e;
            }
            if (d2 <= r2) mark[j] = 1;
          }
        }
  }
  std::vector<long> ids;
  for (int j = 0; j < n; ++j)
    if (mark[j]) ids.push_back(j);
  return ids;
}

} // namespace

LocalPart local_part(const particles::ParticleSet& whole, const Ranks& ranks, double reach) {
  const int n = whole.size();
  for (int i = 0; i < n; ++i)
    MF_REQUIRE(whole.id[i] == i, "distribution: the whole body must be numbered by its ids");
  const IdBlocks blocks{n, ranks.size};
  LocalPart part;
  part.first = blocks.first(ranks.rank);
  const long end = blocks.first(ranks.rank + 1);
  particles::ParticleSet& p = part.particles;
  std::vector<long> owned;
  // Each particle held is a copy of the whole body's, every registered array with it.
  for (long i = part.first; i < end; ++i) {
    p.add_copy(whole, static_cast<int>(i));
    owned.push_back(i);
  }
  // Ids sorted increasingly are grouped by owner: the blocks are contiguous.
  const std::vector<long> ghosts = ghost_ids(whole, part.first, end, reach);
  std::vector<int> owner(ghosts.size());
  for (std::size_t k = 0; k < ghosts.size(); ++k) owner[k] = blocks.owner(ghosts[k]);
  for (long j : ghosts) p.add_ghost(whole, static_cast<int>(j));
  p.time = whole.time;
  p.step = whole.step;
  part.local_of.assign(n, -1);
  for (int i : p.all()) part.local_of[p.id[i]] = i;
  part.halo = Halo(ranks, owned, ghosts, owner);
  return part;
}

void keep_owned(std::vector<int>& group, const LocalPart& part) {
  std::vector<char> none;
  keep_owned(group, none, part);
}

} // namespace mf::distribution
