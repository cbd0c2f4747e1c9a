#pragma once
// Compressed rows computed in parallel: each OpenMP thread fills a contiguous block of rows and the
// blocks are joined in order, so the result does not depend on the number of threads.
#include <omp.h>
#include <vector>

namespace mf {

/// Appends rows 0..n-1 to (offset, index), offset holding its leading 0 already: fill_row(i, row)
/// writes row i into the cleared vector `row`.
template <class Offset, class FillRow>
void parallel_rows(int n, FillRow fill_row, std::vector<Offset>& offset, std::vector<int>& index) {
  std::vector<std::vector<int>> counts, lists;
#pragma omp parallel
  {
#pragma omp single
    {
      counts.resize(omp_get_num_threads());
      lists.resize(omp_get_num_threads());
    }
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int begin = static_cast<int>(static_cast<long>(n) * t / nt);
    const int end = static_cast<int>(static_cast<long>(n) * (t + 1) / nt);
    std::vector<int> row;
    for (int i = begin; i < end; ++i) {
      row.clear();
      fill_row(i, row);
      counts[t].push_back(static_cast<int>(row.size()));
      lists[t].insert(lists[t].end(), row.begin(), row.end());
    }
  }
  offset.reserve(offset.size() + n);
  for (std::size_t t = 0; t < counts.size(); ++t) {
    for (int c : counts[t]) offset.push_back(offset.back() + c);
    index.insert(index.end(), lists[t].begin(), lists[t].end());
  }
}

} // namespace mf
