#include "meshfree/implicit/volumetric_projection.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <unordered_map>

namespace mf::implicit {

namespace {

/// The rows of each cell, in the order of the cells' first rows.
std::vector<std::vector<int>> rows_by_cell(const std::vector<int>& cell) {
  std::unordered_map<int, int> slot;
  std::vector<std::vector<int>> rows;
  for (int r = 0; r < static_cast<int>(cell.size()); ++r) {
    const auto [it, fresh] = slot.emplace(cell[r], static_cast<int>(rows.size()));
    if (fresh) rows.emplace_back();
    rows[it->second].push_back(r);
  }
  return rows;
}

/// shift[j] = mean over the rows of gradient[j] - gradient[j], rows of one cell.
void shift_to_mean(const SolidShapeTable& t, const std::vector<int>& rows,
                   const std::vector<double>& weight, const std::vector<Vec3>& gradient,
                   std::vector<Vec3>& shift) {
  const int n = t.offset[rows[0] + 1] - t.offset[rows[0]];
  std::vector<Vec3> mean(n, Vec3::Zero());
  double volume = 0.0;
  for (int r : rows) {
    MF_ASSERT(t.offset[r + 1] - t.offset[r] == n &&
              std::equal(t.node.begin() + t.offset[r], t.node.begin() + t.offset[r + 1],
                         t.node.begin() + t.offset[rows[0]]));
    for (int a = 0; a < n; ++a) mean[a] += weight[r] * gradient[t.offset[r] + a];
    volume += weight[r];
  }
  for (Vec3& g : mean) g /= volume;
  for (int r : rows)
    for (int a = 0; a < n; ++a) shift[t.offset[r] + a] = mean[a] - gradient[t.offset[r] + a];
}

} // namespace

Csr cell_supports(const Csr& support, const std::vector<int>& cell) {
  MF_ASSERT(static_cast<int>(cell.size()) == support.rows());
  const std::vector<std::vector<int>> rows = rows_by_cell(cell);
  std::vector<std::vector<int>> merged(support.rows());
  for (const std::vector<int>& of_cell : rows) {
    std::vector<int> nodes;
    for (int r : of_cell)
      nodes.insert(nodes.end(), support.index.begin() + support.offset[r],
                   support.index.begin() + support.offset[r + 1]);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (int r : of_cell) merged[r] = nodes;
  }
  Csr out;
  for (const std::vector<int>& nodes : merged) {
    out.index.insert(out.index.end(), nodes.begin(), nodes.end());
    out.offset.push_back(static_cast<int>(out.index.size()));
  }
  return out;
}

void project_volumetric_strain(SolidShapeTable& t, const std::vector<int>& cell,
                               const std::vector<double>& weight) {
  MF_ASSERT(static_cast<int>(cell.size()) == t.rows() && weight.size() == cell.size());
  t.volumetric_shift.assign(t.dphi.size(), Vec3::Zero());
  if (!t.test_dphi.empty()) t.test_volumetric_shift.assign(t.dphi.size(), Vec3::Zero());
  for (const std::vector<int>& rows : rows_by_cell(cell)) {
    shift_to_mean(t, rows, weight, t.dphi, t.volumetric_shift);
    if (!t.test_dphi.empty()) shift_to_mean(t, rows, weight, t.test_dphi, t.test_volumetric_shift);
  }
}

} // namespace mf::implicit
