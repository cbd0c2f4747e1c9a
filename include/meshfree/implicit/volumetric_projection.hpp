#pragma once
// The volumetric strain of a 3D body projected onto the constants of each background cell or
// element: the B-bar method (Hughes 1980; for reproducing-kernel approximations, Chen et al.
// 2000). Every Gauss point of a cell takes the cell's mean volumetric strain and keeps its own
// deviatoric strain,
//   eps_bar = eps + m (theta_mean - theta) / 3,  theta_mean = sum_g w_g theta_g / sum_g w_g,
// m = [1 1 1 0 0 0], so a cell carries one incompressibility constraint instead of one per Gauss
// point and isochoric plastic flow does not lock. A linear displacement field has theta_mean =
// theta, and a constant stress's mean pressure does no work on the shifts (they sum to zero over
// a cell): the patch test holds as without the projection. The map d -> eps_bar is linear, so
// the consistent tangent B_bar^T C B_bar keeps Newton's rate.
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/solid_space.hpp"
#include <unordered_map>
#include <utility>
#include <vector>

namespace mf::implicit {

/// Each point's support widened to the union of the supports of its cell's points (`cell`, per
/// point), sorted: every row of a cell then lists the same nodes, and the nodes of the cell's
/// mean strain.
Csr cell_supports(const Csr& support, const std::vector<int>& cell);

/// Sets the table's volumetric shifts (SolidShapeTable::volumetric_shift): at each row of a
/// cell, the mean over the cell's rows (weights `weight`) of each node's gradient less the
/// row's own, for the trial functions and for the test functions where they differ. The rows of
/// a cell must list the same nodes (cell_supports) and all be in the table (`cell`, per row).
void project_volumetric_strain(SolidShapeTable& t, const std::vector<int>& cell,
                               const std::vector<double>& weight);

/// The Gauss points of a body, all of them, with their cells: where points that are not Gauss
/// points (output samples, a stage's particles) find the cell whose mean they take.
struct CellPoints {
  const std::vector<Vec3>& x;
  const std::vector<double>& weight;
  const std::vector<int>& cell;
  double reach; // the nearest Gauss point of any point of the body is nearer than this
};

/// Gives the rows of `t` (shapes with gradients at `at`) the volumetric strain of a cell's mean:
/// each point takes the cell of its nearest Gauss point, its row is widened by that cell's nodes
/// and gets the shifts to the cell's mean gradients, which `shapes(points)` (shape functions with
/// gradients of the plain space at the cell's points) gives. Passive points then carry the
/// strain the body's Gauss points are given.
template <class Shapes>
void sample_cell_means(const CellPoints& g, const std::vector<Vec3>& at, SolidShapeTable& t,
                       Shapes&& shapes);

namespace cell_means {
using MeanGradients = std::vector<std::pair<int, Vec3>>; // (node, cell-mean gradient), by node
/// The cell of each point of `at`: that of its nearest Gauss point.
std::vector<int> cells_at(const CellPoints& g, const std::vector<Vec3>& at);
/// The Gauss points of each cell.
std::unordered_map<int, std::vector<int>> points_by_cell(const CellPoints& g);
/// The weighted mean gradient of each node over a cell's points (`table` their plain shapes).
MeanGradients mean_gradients(const SolidShapeTable& table, const std::vector<double>& weight);
/// t with each row r widened by the nodes of means.at(cell[r]) and given its shifts.
SolidShapeTable widened(const SolidShapeTable& t, const std::vector<int>& cell,
                        const std::unordered_map<int, MeanGradients>& means);
} // namespace cell_means

template <class Shapes>
void sample_cell_means(const CellPoints& g, const std::vector<Vec3>& at, SolidShapeTable& t,
                       Shapes&& shapes) {
  const std::vector<int> cell = cell_means::cells_at(g, at);
  const std::unordered_map<int, std::vector<int>> members = cell_means::points_by_cell(g);
  std::unordered_map<int, cell_means::MeanGradients> means;
  for (int c : cell) {
    if (means.count(c)) continue;
    std::vector<Vec3> x;
    std::vector<double> w;
    for (int q : members.at(c)) x.push_back(g.x[q]), w.push_back(g.weight[q]);
    means.emplace(c, cell_means::mean_gradients(shapes(x), w));
  }
  t = cell_means::widened(t, cell, means);
}

} // namespace mf::implicit
