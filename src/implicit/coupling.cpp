#include "meshfree/implicit/coupling.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/memory.hpp"
#include <algorithm>

namespace mf::implicit {

namespace {

/// The first element of the sorted range [k, end) not below x, by galloping from k: the nodes of
/// a point lie close together among the columns of a row (about 4 columns apart where a row has
/// 45 and the point 12 nodes), so this takes 1 to 3 comparisons where a binary search over the
/// rest of the row takes 5 or 6; a coarse node next to a refined region, whose row holds
/// thousands of columns, still costs a logarithm of the distance.
inline const int* gallop(const int* k, const int* end, int x) {
  if (k == end || *k >= x) return k;
  std::ptrdiff_t hi = 1; // k[hi / 2] < x throughout
  while (hi < end - k && k[hi] < x) hi *= 2;
  return std::lower_bound(k + hi / 2 + 1, k + std::min<std::ptrdiff_t>(hi, end - k), x);
}

} // namespace

RowPattern coupling_pattern(const std::vector<const Csr*>& lists, int node_count, int begin,
                            int end) {
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
  RowPattern p;
  p.begin = begin;
  p.end = end;
  p.offset.assign(owned + 1, 0);
  std::vector<int> stamp(node_count, -1);
  for (int i = 0; i < owned; ++i) {
    const std::size_t row_start = p.column.size();
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const Csr& c = *lists[rows[k].first];
      const int r = rows[k].second;
      for (int q = c.offset[r]; q < c.offset[r + 1]; ++q) {
        const int J = c.index[q];
        if (stamp[J] == i) continue;
        stamp[J] = i;
        p.column.push_back(J);
      }
    }
    std::sort(p.column.begin() + static_cast<long>(row_start), p.column.end());
    p.offset[i + 1] = static_cast<int>(p.column.size());
  }
  return p;
}

namespace {

int checked_dofs(int dofs) {
  MF_REQUIRE(dofs == 2 || dofs == 3, "BlockRows: ", dofs, " DOFs per node (2 or 3 are held)");
  return dofs;
}

} // namespace

BlockRows::BlockRows(const RowPattern& pattern, int dofs)
    : pattern_(&pattern), dofs_(checked_dofs(dofs)),
      rhs_(dofs * static_cast<std::size_t>(pattern.rows()), 0.0) {
  set_layout();
  own_.assign(diagonal_values_ + off_values_, 0.0);
  diagonal_ = own_.data();
  off_ = own_.data() + diagonal_values_;
}

BlockRows::BlockRows(const RowPattern& pattern, solvers::BlockValueArrays values, int dofs)
    : pattern_(&pattern), dofs_(checked_dofs(dofs)),
      rhs_(dofs * static_cast<std::size_t>(pattern.rows()), 0.0) {
  set_layout();
  MF_REQUIRE((values.diagonal || diagonal_values_ == 0) &&
                 (values.off_diagonal || off_values_ == 0),
             "BlockRows: the matrix has no storage for some of its blocks");
  diagonal_ = values.diagonal;
  off_ = values.off_diagonal;
}

void BlockRows::set_layout() {
  const RowPattern& p = *pattern_;
  // dofs scalar rows of dofs values per block.
  const std::size_t block_values = static_cast<std::size_t>(dofs_) * dofs_;
  layout_.resize(p.rows());
  for (int i = 0; i < p.rows(); ++i) {
    const int* first = p.column.data() + p.offset[i];
    const int* last = p.column.data() + p.offset[i + 1];
    const int* own_begin = std::lower_bound(first, last, p.begin);
    const int* own_end = std::lower_bound(own_begin, last, p.end);
    RowLayout& L = layout_[i];
    L.diagonal_begin = static_cast<int>(own_begin - p.column.data());
    L.diagonal_end = static_cast<int>(own_end - p.column.data());
    L.diagonal_start = diagonal_values_;
    L.off_start = off_values_;
    diagonal_values_ += block_values * static_cast<std::size_t>(own_end - own_begin);
    off_values_ += block_values * static_cast<std::size_t>((last - first) - (own_end - own_begin));
  }
}

void BlockRows::add_matrix(const int* nodes, int n, const double* block) {
  if (dofs_ == 3)
    add_matrix_dofs<3>(nodes, n, block);
  else
    add_matrix_dofs<2>(nodes, n, block);
}

template <int D> void BlockRows::add_matrix_dofs(const int* nodes, int n, const double* block) {
  const RowPattern& p = *pattern_;
  const int stride = D * n;
  for (int a = 0; a < n; ++a) {
    const int I = nodes[a];
    if (I < p.begin || I >= p.end) continue;
    const int row = I - p.begin;
    // Both the row's columns and `nodes` are sorted: each search starts where the last ended.
    const int* col = p.column.data();
    const int* k_end = col + p.offset[row + 1];
    const int* k = col + p.offset[row];
    for (int b = 0; b < n; ++b) {
      k = gallop(k, k_end, nodes[b]);
      MF_ASSERT(k < k_end && *k == nodes[b]);
      int s;
      double* v = block_at<D>(row, static_cast<int>(k - col), s);
      const double* src = block + (D * a) * stride + D * b;
      for (int c = 0; c < D; ++c)
        for (int e = 0; e < D; ++e) v[c * s + e] += src[c * stride + e];
    }
  }
}

void BlockRows::add_matrix_at(const int* nodes, const int* slots, int n, const double* block) {
  if (dofs_ == 3)
    add_matrix_at_dofs<3>(nodes, slots, n, block);
  else
    add_matrix_at_dofs<2>(nodes, slots, n, block);
}

template <int D>
void BlockRows::add_matrix_at_dofs(const int* nodes, const int* slots, int n, const double* block) {
  const int stride = D * n;
  for (int a = 0; a < n; ++a) {
    const int row = nodes[a] - pattern_->begin;
    for (int b = 0; b < n; ++b) {
      const int k = slots[a * n + b];
      if (k < 0) continue;
      int s;
      double* v = block_at<D>(row, k, s);
      const double* src = block + (D * a) * stride + D * b;
      for (int c = 0; c < D; ++c)
        for (int e = 0; e < D; ++e) v[c * s + e] += src[c * stride + e];
    }
  }
}

void BlockRows::copy_values(const BlockRows& other) {
  MF_REQUIRE(other.pattern_ == pattern_ && other.dofs_ == dofs_,
             "BlockRows::copy_values: another pattern");
  std::copy(other.diagonal_, other.diagonal_ + diagonal_values_, diagonal_);
  if (off_values_ > 0) std::copy(other.off_, other.off_ + off_values_, off_);
}

void BlockRows::multiply_add(const std::vector<double>& d, double* r) const {
  if (dofs_ == 3)
    multiply_add_dofs<3>(d, r);
  else
    multiply_add_dofs<2>(d, r);
}

template <int D> void BlockRows::multiply_add_dofs(const std::vector<double>& d, double* r) const {
  const RowPattern& p = *pattern_;
  for (int i = 0; i < p.rows(); ++i) {
    double sum[D] = {};
    for (int k = p.offset[i]; k < p.offset[i + 1]; ++k) {
      int s;
      const double* b = block_at<D>(i, k, s);
      const double* dJ = d.data() + D * static_cast<std::size_t>(p.column[k]);
      // Each row of the block summed first, then added: (b0 dx + b1 dy) as one term.
      for (int c = 0; c < D; ++c) {
        double t = b[c * s] * dJ[0];
        for (int e = 1; e < D; ++e) t += b[c * s + e] * dJ[e];
        sum[c] += t;
      }
    }
    for (int c = 0; c < D; ++c) r[D * static_cast<std::size_t>(i) + c] += sum[c];
  }
}

BlockScatter::BlockScatter(const std::vector<int>& row_offset, const std::vector<int>& row_node,
                           const RowPattern& p, double max_bytes)
    : row_offset_(row_offset), row_node_(row_node), pattern_(p) {
  const int rows = static_cast<int>(row_offset.size()) - 1;
  offset_.assign(rows + 1, 0);
  for (int r = 0; r < rows; ++r) {
    const std::size_t n = row_offset[r + 1] - row_offset[r];
    offset_[r + 1] = offset_[r] + n * n;
  }
  if (max_bytes < 0.0) max_bytes = 0.25 * usable_memory();
  kept_ = max_bytes <= 0.0 ? false : full_bytes() <= max_bytes;
  if (!kept_) return;
  slot_.resize(offset_.back());
  for (int r = 0; r < rows; ++r) find(r, slot_.data() + offset_[r]);
}

void BlockScatter::find(int r, int* out) const {
  const RowPattern& p = pattern_;
  const int* col = p.column.data();
  const int n = row_offset_[r + 1] - row_offset_[r];
  const int* nodes = row_node_.data() + row_offset_[r];
  std::fill(out, out + static_cast<std::size_t>(n) * n, -1);
  for (int a = 0; a < n; ++a) {
    const int I = nodes[a];
    if (I < p.begin || I >= p.end) continue;
    const int* k = col + p.offset[I - p.begin];
    const int* k_end = col + p.offset[I - p.begin + 1];
    for (int b = 0; b < n; ++b) {
      k = gallop(k, k_end, nodes[b]);
      MF_REQUIRE(k < k_end && *k == nodes[b], "BlockScatter: a node pair is not in the pattern");
      out[a * n + b] = static_cast<int>(k - col);
    }
  }
}

void BlockRows::add_vector(const int* nodes, int n, const double* values) {
  const RowPattern& p = *pattern_;
  for (int a = 0; a < n; ++a) {
    const int I = nodes[a];
    if (I < p.begin || I >= p.end) continue;
    for (int c = 0; c < dofs_; ++c)
      rhs_[dofs_ * static_cast<std::size_t>(I - p.begin) + c] += values[dofs_ * a + c];
  }
}

} // namespace mf::implicit
