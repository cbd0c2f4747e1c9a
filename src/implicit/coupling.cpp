#include "meshfree/implicit/coupling.hpp"

namespace mf::implicit {

void coupling_counts(const std::vector<const Csr*>& lists, int node_count, int begin, int end,
                     std::vector<int>& inside, std::vector<int>& outside) {
  const int owned = end - begin;
  // Transpose: for each owned node, the (list, row) pairs whose support contains it.
  std::vector<int> start(owned + 1, 0);
  for (const Csr* c : lists)
    for (int node : c->index)
      if (node >= begin && node < end) ++start[node - begin + 1];
  for (int i = 0; i < owned; ++i) start[i + 1] += start[i];
  std::vector<std::pair<int, int>> rows(start[owned]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int l = 0; l < static_cast<int>(lists.size()); ++l) {
    const Csr& c = *lists[l];
    for (int r = 0; r < c.rows(); ++r)
      for (int k = c.offset[r]; k < c.offset[r + 1]; ++k) {
        const int node = c.index[k];
        if (node >= begin && node < end) rows[fill[node - begin]++] = {l, r};
      }
  }
  inside.assign(owned, 0);
  outside.assign(owned, 0);
  std::vector<int> stamp(node_count, -1);
  for (int i = 0; i < owned; ++i)
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const Csr& c = *lists[rows[k].first];
      const int r = rows[k].second;
      for (int q = c.offset[r]; q < c.offset[r + 1]; ++q) {
        const int J = c.index[q];
        if (stamp[J] == i) continue;
        stamp[J] = i;
        (J >= begin && J < end ? inside[i] : outside[i])++;
      }
    }
}

} // namespace mf::implicit
