#pragma once
// The volumetric strain of a body projected onto the constants of each background cell or
// element: the B-bar method (Hughes 1980; for reproducing-kernel approximations, Chen et al.
// 2000). Every Gauss point of a cell takes the cell's mean volumetric strain,
//   eps_bar = eps + m (theta_mean - theta) / dim,  theta_mean = sum_g w_g theta_g / sum_g w_g,
// so a cell carries one incompressibility constraint instead of one per Gauss point and
// isochoric plastic flow does not lock. In 3D m = [1 1 1 0 0 0] and the point keeps its own
// deviatoric strain. In plane strain eps_zz = 0 must hold, so m = [1 1 0] spreads the change
// over the in-plane normal strains (the small-strain form of de Souza Neto et al. 2008, §15.2's
// plane-strain F-bar, whose factor (J_mean / J)^(1/2) scales the in-plane deformation only):
// the in-plane deviator [e_xx - e_yy, e_xy] is kept. A linear displacement field has theta_mean =
// theta, and a constant stress's mean pressure does no work on the shifts (they sum to zero over
// a cell): the patch test holds as without the projection. The map d -> eps_bar is linear, so
// the consistent tangent B_bar^T C B_bar keeps Newton's rate.
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/shape_table.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <algorithm>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mf::implicit {

/// The Gauss order of a finite-element body whose input gives none (discretisation.fem.order):
/// 8-node quadrilaterals and 20-node bricks of an elastoplastic plane-strain or 3D body take the
/// reduced rule, 2 points a direction, as CalculiX's CPE8R and C3D20R: on the full rule their
/// isochoric plastic flow locks (a 3D punch 17.5% short against 1.7% reduced; a plastic cylinder
/// carried 4% past its limit pressure 192.09 MPa, to 199.8, where on the reduced rule its
/// stiffness is gone at 191.61). Every other body takes its element's own order,
/// `element_default`.
int default_fe_order(const spec::ProblemSpec& spec, const spec::DiscretisationSpec& d,
                     int element_default);

/// Warns (naming the key) where 8-node quadrilaterals or 20-node bricks take the cell mean: one
/// mean volumetric strain an element is too few constraints for them, and they run too soft (Q8 on
/// Kirsch's plate at nu = 0.3: energy error 1.6% against 0.15% pointwise; hex20 31% too soft
/// under a punch); they take the reduced rule instead.
void warn_quadratic_cell_mean(const spec::DiscretisationSpec& d);

/// Each point's support widened to the union of the supports of its cell's points (`cell`, per
/// point), sorted: every row of a cell then lists the same nodes, and the nodes of the cell's
/// mean strain.
Csr cell_supports(const Csr& support, const std::vector<int>& cell);

/// Sets the table's volumetric shifts (SolidShapeTable::volumetric_shift): at each row of a
/// cell, the mean over the cell's rows (weights `weight`) of each node's gradient less the
/// row's own, for the trial functions and for the test functions where they differ. The rows of
/// a cell must list the same nodes (cell_supports) and all be in the table (`cell`, per row).
template <int dim>
void project_volumetric_strain(ShapeTableOf<dim>& t, const std::vector<int>& cell,
                               const std::vector<double>& weight);

/// Gives a plane or solid model's domain table the volumetric strain of its cells' means where
/// its discretisation asks for it (`cell_of_point`: the cell of each of the body's points, which
/// the rows m.domain_mine.rows index), with the reach of its passive points' search; warns where
/// quadratic elements take it.
template <class Model>
void take_cell_means(Model& m, const std::vector<int>& cell_of_point,
                     const spec::DiscretisationSpec& d) {
  if (!d.cell_mean_volumetric) return;
  warn_quadratic_cell_mean(d);
  m.cell_mean = true;
  m.cell_reach = 2.0 * std::max(d.spacing, d.cell_size);
  std::vector<int> cell;
  for (int r : m.domain_mine.rows) cell.push_back(cell_of_point[r]);
  project_volumetric_strain(m.domain_table, cell, m.domain_weight);
}

/// The Gauss points of a body, all of them, with their cells: where points that are not Gauss
/// points (output samples, a stage's particles) find the cell whose mean they take.
template <int dim> struct CellPoints {
  const std::vector<Eigen::Matrix<double, dim, 1>>& x;
  const std::vector<double>& weight;
  const std::vector<int>& cell;
  double reach; // the nearest Gauss point of any point of the body is nearer than this
};

/// Gives the rows of `t` (shapes with gradients at `at`) the volumetric strain of a cell's mean:
/// each point takes the cell of its nearest Gauss point, its row is widened by that cell's nodes
/// and gets the shifts to the cell's mean gradients, which `shapes(points)` (shape functions with
/// gradients of the plain space at the cell's points) gives. Passive points then carry the
/// strain the body's Gauss points are given.
template <int dim, class Shapes>
void sample_cell_means(const CellPoints<dim>& g,
                       const std::vector<Eigen::Matrix<double, dim, 1>>& at, ShapeTableOf<dim>& t,
                       Shapes&& shapes);

namespace cell_means {
/// (node, cell-mean gradient), by node
template <int dim> using MeanGradients = std::vector<std::pair<int, Eigen::Matrix<double, dim, 1>>>;
/// The cell of each point of `at`: that of its nearest Gauss point.
template <int dim>
std::vector<int> cells_at(const CellPoints<dim>& g,
                          const std::vector<Eigen::Matrix<double, dim, 1>>& at);
/// The Gauss points of each cell.
std::unordered_map<int, std::vector<int>> points_by_cell(const std::vector<int>& cell);
/// The weighted mean gradient of each node over a cell's points (`table` their plain shapes).
template <int dim>
MeanGradients<dim> mean_gradients(const ShapeTableOf<dim>& table,
                                  const std::vector<double>& weight);
/// t with each row r widened by the nodes of means.at(cell[r]) and given its shifts.
template <int dim>
ShapeTableOf<dim> widened(const ShapeTableOf<dim>& t, const std::vector<int>& cell,
                          const std::unordered_map<int, MeanGradients<dim>>& means);
} // namespace cell_means

template <int dim, class Shapes>
void sample_cell_means(const CellPoints<dim>& g,
                       const std::vector<Eigen::Matrix<double, dim, 1>>& at, ShapeTableOf<dim>& t,
                       Shapes&& shapes) {
  const std::vector<int> cell = cell_means::cells_at(g, at);
  const std::unordered_map<int, std::vector<int>> members = cell_means::points_by_cell(g.cell);
  std::unordered_map<int, cell_means::MeanGradients<dim>> means;
  for (int c : cell) {
    if (means.count(c)) continue;
    std::vector<Eigen::Matrix<double, dim, 1>> x;
    std::vector<double> w;
    for (int q : members.at(c)) x.push_back(g.x[q]), w.push_back(g.weight[q]);
    means.emplace(c, cell_means::mean_gradients(shapes(x), w));
  }
  t = cell_means::widened(t, cell, means);
}

} // namespace mf::implicit
