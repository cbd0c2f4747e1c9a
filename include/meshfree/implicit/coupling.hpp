#pragma once
// Exact sparsity of a meshfree Galerkin matrix: nodes I and J couple when some integration
// point lies in both supports.
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <algorithm>
#include <cstddef>
#include <vector>

namespace mf::implicit {

/// The block rows [begin, end) of the matrix: for row I, the sorted nodes it couples to.
struct RowPattern {
  int begin = 0, end = 0;
  std::vector<int> offset{0}; // per owned row
  std::vector<int> column;    // global node indices, sorted within each row
  int rows() const { return end - begin; }
};

/// Pattern of rows [begin, end) over the support lists of every point in `lists`.
RowPattern coupling_pattern(const std::vector<const Csr*>& lists, int node_count, int begin,
                            int end);

/// Every node named by the pattern's columns, the domain table's rows and each condition's table
/// (`conditions`: items with a `table.node` list), sorted and once: the entries of d that a
/// residual over these rows reads.
template <class Conditions>
std::vector<int> nodes_read(const std::vector<int>& domain_nodes, const RowPattern& pattern,
                            const Conditions& conditions) {
  std::vector<int> nodes(domain_nodes);
  nodes.insert(nodes.end(), pattern.column.begin(), pattern.column.end());
  for (const auto& c : conditions)
    nodes.insert(nodes.end(), c.table.node.begin(), c.table.node.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

/// The dofs x dofs blocks (2 or 3 DOFs per node) of the rows [pattern.begin, pattern.end) of a
/// sparse matrix with a fixed pattern, and the matching right-hand side. Contributions to other
/// rows are dropped: the rank that owns them integrates the same points. The values are in the
/// order of a PETSc matrix's storage (solvers::BlockValueArrays): in their own arrays, or in a
/// matrix's, written in place. The pattern is the model's, which must outlive the rows: a copy
/// would be another 4 bytes per block to page in at every assembly.
class BlockRows {
public:
  /// Zero values in arrays of their own.
  explicit BlockRows(const RowPattern& pattern, int dofs = 2);
  /// The values of a matrix made on `pattern` with the same DOFs per node
  /// (solvers::BlockLinearSystem, the Jacobian of a solvers::NonlinearBlockSystem), which must
  /// outlive the rows.
  BlockRows(const RowPattern& pattern, solvers::BlockValueArrays values, int dofs = 2);

  /// Adds a (dofs n x dofs n, row-major) block on nodes[0..n), which must be sorted.
  void add_matrix(const int* nodes, int n, const double* block);
  /// The same with the slots of the (row, column) pairs known (BlockScatter): no search.
  void add_matrix_at(const int* nodes, const int* slots, int n, const double* block);
  /// Adds dofs n values, dofs per node of nodes[0..n), to the right-hand side.
  void add_vector(const int* nodes, int n, const double* values);

  /// Overwrites the values with those of `other`, on the same pattern.
  void copy_values(const BlockRows& other);
  /// r[dofs i + c] += sum_J (block_IJ d_J)_c over the owned rows i; `d` is the full-length vector.
  void multiply_add(const std::vector<double>& d, double* r) const;

  const RowPattern& pattern() const { return *pattern_; }
  const std::vector<double>& rhs() const { return rhs_; }
  int dofs() const { return dofs_; }

private:
  /// Where a block row's values lie: its owned block columns are the pattern entries
  /// [diagonal_begin, diagonal_end), at diagonal_start in the diagonal array; the others at
  /// off_start in the off-diagonal one (D values per block in each of the D scalar rows).
  struct RowLayout {
    int diagonal_begin, diagonal_end;
    std::size_t diagonal_start, off_start;
  };
  /// The upper-left value of the block of pattern entry k in block row `row`, with D DOFs per
  /// node; each next row of the block lies `stride` values further on.
  template <int D> double* block_at(int row, int k, int& stride) const {
    const RowLayout& L = layout_[row];
    const int diagonal = L.diagonal_end - L.diagonal_begin;
    if (k >= L.diagonal_begin && k < L.diagonal_end) {
      stride = D * diagonal;
      return diagonal_ + L.diagonal_start + D * (k - L.diagonal_begin);
    }
    const int first = pattern_->offset[row];
    stride = D * (pattern_->offset[row + 1] - first - diagonal);
    return off_ + L.off_start + D * (k - first - (k >= L.diagonal_end ? diagonal : 0));
  }
  // The loops over the entries, with the DOFs per node a constant (coupling.cpp).
  template <int D> void add_matrix_dofs(const int* nodes, int n, const double* block);
  template <int D>
  void add_matrix_at_dofs(const int* nodes, const int* slots, int n, const double* block);
  template <int D> void multiply_add_dofs(const std::vector<double>& d, double* r) const;
  void set_layout();

  const RowPattern* pattern_;
  int dofs_;
  std::vector<RowLayout> layout_;
  std::size_t diagonal_values_ = 0, off_values_ = 0;
  std::vector<double> own_; // the values, where they are not a matrix's
  double* diagonal_ = nullptr;
  double* off_ = nullptr;
  std::vector<double> rhs_;
};

/// Where each (owned row, column) node pair of every point of a shape table lands among the
/// blocks of a row pattern: n * n slots per point (row-major, -1 for rows another rank owns).
/// Assembling a point then costs indexed additions instead of searches in the rows, which is
/// worth its memory (4 bytes per pair) for a matrix assembled at every Newton iteration: the
/// searches cost more than the element arithmetic (measured in README.md, "Running"). Where
/// the map would take more than `max_bytes` (by default a quarter of the memory here: some
/// 0.7 GB per million points of 12 nodes), it is not kept and each point's slots are searched
/// anew when asked for, into a buffer given by the caller (one per thread).
class BlockScatter {
public:
  BlockScatter(const ShapeTable& table, const RowPattern& pattern, double max_bytes = -1.0)
      : BlockScatter(table.offset, table.node, pattern, max_bytes) {}
  /// The same for any table of points given by its compressed rows of nodes (a 3D table).
  BlockScatter(const std::vector<int>& row_offset, const std::vector<int>& row_node,
               const RowPattern& pattern, double max_bytes = -1.0);
  /// Point r's n * n slots: in the map, or searched into `buffer`.
  const int* slots(int r, std::vector<int>& buffer) const {
    if (kept_) return slot_.data() + offset_[r];
    const int n = row_offset_[r + 1] - row_offset_[r];
    buffer.resize(static_cast<std::size_t>(n) * n);
    find(r, buffer.data());
    return buffer.data();
  }
  /// Bytes the map holds (0 when it was not kept).
  std::size_t bytes() const { return slot_.size() * sizeof(int); }
  bool kept() const { return kept_; }
  /// Bytes the whole map takes.
  double full_bytes() const { return static_cast<double>(offset_.back()) * sizeof(int); }

private:
  void find(int r, int* out) const;
  const std::vector<int>& row_offset_; // the table's rows of nodes
  const std::vector<int>& row_node_;
  const RowPattern& pattern_;
  std::vector<std::size_t> offset_;
  std::vector<int> slot_;
  bool kept_ = true;
};

} // namespace mf::implicit
