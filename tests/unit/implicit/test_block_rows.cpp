// Block rows of a distributed matrix: the values land in the order of PETSc's AIJ storage
// (per scalar row the owned columns, then the others, each in column order), whichever way a
// point's block is added.
#include "meshfree/implicit/coupling.hpp"
#include <algorithm>
#include <catch2/catch.hpp>

using namespace mf;
using namespace mf::implicit;

namespace {

constexpr int kNodes = 6;
constexpr int kBegin = 2, kEnd = 4; // the owned rows: columns on both sides are off-diagonal

/// Three points over the six nodes; node lists sorted, as in a shape table.
ShapeTable points() {
  ShapeTable t;
  t.node = {0, 2, 3, 2, 4, 5, 1, 3};
  t.offset = {0, 3, 6, 8};
  return t;
}

/// A distinct value for every entry of every point's block.
std::vector<double> point_block(int r, int n) {
  std::vector<double> b(4 * n * n);
  for (std::size_t q = 0; q < b.size(); ++q) b[q] = 100.0 * (r + 1) + static_cast<double>(q);
  return b;
}

/// The dense matrix of the owned rows that the points add up to.
std::vector<double> dense(const ShapeTable& t) {
  std::vector<double> K(4 * kNodes * kNodes, 0.0);
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const std::vector<double> b = point_block(r, n);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < n; ++c)
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j) {
            const int I = t.node[t.offset[r] + a], J = t.node[t.offset[r] + c];
            if (I >= kBegin && I < kEnd)
              K[(2 * I + i) * 2 * kNodes + 2 * J + j] += b[(2 * a + i) * 2 * n + 2 * c + j];
          }
  }
  return K;
}

} // namespace

TEST_CASE("block rows: values in PETSc's storage order, by search and by slots alike",
          "[assembly]") {
  const ShapeTable t = points();
  const Csr lists{t.offset, t.node};
  const RowPattern p = coupling_pattern({&lists}, kNodes, kBegin, kEnd);
  // Row 2 couples to 0, 2, 3, 4, 5; row 3 to 0, 1, 2, 3.
  REQUIRE(p.column == std::vector<int>{0, 2, 3, 4, 5, 0, 1, 2, 3});

  // The matrix's storage: 2 owned block columns in each row (4 values per scalar row pair
  // each), 3 and 2 others.
  std::vector<double> diagonal(4 * 4, 0.0), off(4 * 5, 0.0);
  BlockRows in_matrix(p, {diagonal.data(), off.data()});
  BlockRows by_slots(p);
  const BlockScatter scatter(t, p);
  std::vector<int> buffer;
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const std::vector<double> b = point_block(r, n);
    in_matrix.add_matrix(t.node.data() + t.offset[r], n, b.data());
    by_slots.add_matrix_at(t.node.data() + t.offset[r], scatter.slots(r, buffer), n, b.data());
  }

  const std::vector<double> K = dense(t);
  const auto k = [&](int row, int column) { return K[row * 2 * kNodes + column]; };
  // Scalar rows 4, 5 (node 2), then 6, 7 (node 3): owned columns 4..7 in `diagonal`, the others
  // in column order in `off`.
  const std::vector<double> expected_diagonal = {
      k(4, 4), k(4, 5), k(4, 6), k(4, 7), k(5, 4), k(5, 5), k(5, 6), k(5, 7),
      k(6, 4), k(6, 5), k(6, 6), k(6, 7), k(7, 4), k(7, 5), k(7, 6), k(7, 7)};
  const std::vector<double> expected_off = {
      k(4, 0),  k(4, 1),  k(4, 8), k(4, 9), k(4, 10), k(4, 11), k(5, 0), k(5, 1), k(5, 8), k(5, 9),
      k(5, 10), k(5, 11), k(6, 0), k(6, 1), k(6, 2),  k(6, 3),  k(7, 0), k(7, 1), k(7, 2), k(7, 3)};
  CHECK(diagonal == expected_diagonal);
  CHECK(off == expected_off);

  // The same matrix through the slots, and K d by both.
  std::vector<double> d(2 * kNodes);
  for (int q = 0; q < 2 * kNodes; ++q) d[q] = 0.5 + q;
  std::vector<double> r1(4, 0.0), r2(4, 0.0);
  in_matrix.multiply_add(d, r1.data());
  by_slots.multiply_add(d, r2.data());
  for (int i = 0; i < 4; ++i) {
    double exact = 0.0;
    for (int q = 0; q < 2 * kNodes; ++q) exact += k(2 * kBegin + i, q) * d[q];
    CHECK(r1[i] == Approx(exact).epsilon(1e-15));
    CHECK(r2[i] == r1[i]);
  }

  // Copying the values carries them over whole.
  std::fill(diagonal.begin(), diagonal.end(), 0.0);
  std::fill(off.begin(), off.end(), 0.0);
  BlockRows copy(p, {diagonal.data(), off.data()});
  std::vector<double> r3(4, 0.0);
  copy.copy_values(by_slots);
  copy.multiply_add(d, r3.data());
  CHECK(r3 == r1);
}

namespace {

/// A distinct value for every entry of a point's (dofs n x dofs n) block.
std::vector<double> point_block(int r, int n, int dofs) {
  std::vector<double> b(dofs * dofs * n * n);
  for (std::size_t q = 0; q < b.size(); ++q) b[q] = 100.0 * (r + 1) + static_cast<double>(q);
  return b;
}

/// The dense matrix (dofs kNodes square) of the owned rows that the points add up to.
std::vector<double> dense(const ShapeTable& t, int dofs) {
  const int size = dofs * kNodes;
  std::vector<double> K(size * size, 0.0);
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const std::vector<double> b = point_block(r, n, dofs);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < n; ++c) {
        const int I = t.node[t.offset[r] + a], J = t.node[t.offset[r] + c];
        if (I < kBegin || I >= kEnd) continue;
        for (int i = 0; i < dofs; ++i)
          for (int j = 0; j < dofs; ++j)
            K[(dofs * I + i) * size + dofs * J + j] += b[(dofs * a + i) * dofs * n + dofs * c + j];
      }
  }
  return K;
}

/// PETSc's AIJ storage of the owned rows of K on the pattern: per scalar row, the owned block
/// columns' values, then (in `off`) the others', each in column order.
void storage_order(const std::vector<double>& K, const RowPattern& p, int dofs,
                   std::vector<double>& diagonal, std::vector<double>& off) {
  const int size = dofs * kNodes;
  for (int I = p.begin; I < p.end; ++I)
    for (int i = 0; i < dofs; ++i)
      for (int k = p.offset[I - p.begin]; k < p.offset[I - p.begin + 1]; ++k) {
        const int J = p.column[k];
        auto& part = J >= p.begin && J < p.end ? diagonal : off;
        for (int j = 0; j < dofs; ++j) part.push_back(K[(dofs * I + i) * size + dofs * J + j]);
      }
}

} // namespace

TEST_CASE("block rows with 3 DOFs per node: values in PETSc's storage order, by search and by "
          "slots alike, and K d",
          "[assembly]") {
  const int dofs = 3;
  const ShapeTable t = points();
  const Csr lists{t.offset, t.node};
  const RowPattern p = coupling_pattern({&lists}, kNodes, kBegin, kEnd);
  const std::vector<double> K = dense(t, dofs);
  std::vector<double> expected_diagonal, expected_off;
  storage_order(K, p, dofs, expected_diagonal, expected_off);
  // 4 owned and 5 other blocks of 9 values.
  REQUIRE(expected_diagonal.size() == 36);
  REQUIRE(expected_off.size() == 45);

  std::vector<double> diagonal(36, 0.0), off(45, 0.0);
  BlockRows in_matrix(p, {diagonal.data(), off.data()}, dofs);
  BlockRows by_slots(p, dofs);
  CHECK(in_matrix.dofs() == 3);
  const BlockScatter scatter(t, p);
  std::vector<int> buffer;
  for (int r = 0; r < t.rows(); ++r) {
    const int n = t.offset[r + 1] - t.offset[r];
    const std::vector<double> b = point_block(r, n, dofs);
    in_matrix.add_matrix(t.node.data() + t.offset[r], n, b.data());
    by_slots.add_matrix_at(t.node.data() + t.offset[r], scatter.slots(r, buffer), n, b.data());
    // The same node-block vector on the points' nodes: 3 values per node.
    std::vector<double> f(dofs * n);
    for (int q = 0; q < dofs * n; ++q) f[q] = 10.0 * r + q;
    in_matrix.add_vector(t.node.data() + t.offset[r], n, f.data());
  }
  CHECK(diagonal == expected_diagonal);
  CHECK(off == expected_off);
  // Owned nodes 2 and 3: node 2 is point 0's second node (3, 4, 5) and point 1's first (10, 11,
  // 12), node 3 point 0's third (6, 7, 8) and point 2's second (23, 24, 25).
  CHECK(in_matrix.rhs() == std::vector<double>{13, 15, 17, 29, 31, 33});
  CHECK(by_slots.rhs() == std::vector<double>(6, 0.0));

  std::vector<double> d(dofs * kNodes);
  for (int q = 0; q < dofs * kNodes; ++q) d[q] = 0.5 + q;
  std::vector<double> r1(6, 0.0), r2(6, 0.0);
  in_matrix.multiply_add(d, r1.data());
  by_slots.multiply_add(d, r2.data());
  for (int i = 0; i < 6; ++i) {
    double exact = 0.0;
    for (int q = 0; q < dofs * kNodes; ++q)
      exact += K[(dofs * kBegin + i) * dofs * kNodes + q] * d[q];
    CHECK(r1[i] == Approx(exact).epsilon(1e-15));
    CHECK(r2[i] == r1[i]);
  }
}
