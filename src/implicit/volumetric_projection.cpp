#include "meshfree/implicit/volumetric_projection.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/point_coupling.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include <algorithm>
#include <limits>
#include <map>
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
template <int dim, class Gradient = typename ShapeTableOf<dim>::Gradient>
void shift_to_mean(const ShapeTableOf<dim>& t, const std::vector<int>& rows,
                   const std::vector<double>& weight, const std::vector<Gradient>& gradient,
                   std::vector<Gradient>& shift) {
  const int n = t.offset[rows[0] + 1] - t.offset[rows[0]];
  std::vector<Gradient> mean(n, Gradient::Zero());
  double volume = 0.0;
  for (int r : rows) {
    MF_ASSERT(t.offset[r + 1] - t.offset[r] == n &&
              std::equal(t.node.begin() + t.offset[r], t.node.begin() + t.offset[r + 1],
                         t.node.begin() + t.offset[rows[0]]));
    for (int a = 0; a < n; ++a) mean[a] += weight[r] * gradient[t.offset[r] + a];
    volume += weight[r];
  }
  for (Gradient& g : mean) g /= volume;
  for (int r : rows)
    for (int a = 0; a < n; ++a) shift[t.offset[r] + a] = mean[a] - gradient[t.offset[r] + a];
}

} // namespace

int default_fe_order(const spec::ProblemSpec& spec, const spec::DiscretisationSpec& d,
                     int element_default) {
  if (d.fem.order > 0) return d.fem.order;
  const bool quadratic = d.fem.element == "q8" || d.fem.element == "hex20";
  const bool constrained_volume = spec.model_type == spec::ModelType::PlaneStrain ||
                                  spec.model_type == spec::ModelType::Solid3D;
  return quadratic && constrained_volume && spec.analysis == spec::Analysis::ElastoplasticStatic
             ? 2
             : element_default;
}

void warn_quadratic_cell_mean(const spec::DiscretisationSpec& d) {
  const std::string& e = d.fem.element;
  if (!d.cell_mean_volumetric || d.method != spec::Method::Fem || (e != "q8" && e != "hex20"))
    return;
  log::warn("discretisation.quadrature.volumetric_strain: cell_mean gives each ", e,
            " element one mean volumetric strain, too few constraints for a quadratic element: it "
            "runs too soft; quadratic elements take the reduced rule (discretisation.fem.order: 2, "
            "volumetric_strain: pointwise) instead");
}

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

template <int dim>
void project_volumetric_strain(ShapeTableOf<dim>& t, const std::vector<int>& cell,
                               const std::vector<double>& weight) {
  using Gradient = typename ShapeTableOf<dim>::Gradient;
  MF_ASSERT(static_cast<int>(cell.size()) == t.rows() && weight.size() == cell.size());
  t.volumetric_shift.assign(t.dphi.size(), Gradient::Zero());
  if (!t.test_dphi.empty()) t.test_volumetric_shift.assign(t.dphi.size(), Gradient::Zero());
  for (const std::vector<int>& rows : rows_by_cell(cell)) {
    shift_to_mean(t, rows, weight, t.dphi, t.volumetric_shift);
    if (!t.test_dphi.empty()) shift_to_mean(t, rows, weight, t.test_dphi, t.test_volumetric_shift);
  }
}

template void project_volumetric_strain(ShapeTable&, const std::vector<int>&,
                                        const std::vector<double>&);
template void project_volumetric_strain(SolidShapeTable&, const std::vector<int>&,
                                        const std::vector<double>&);

} // namespace mf::implicit

namespace mf::implicit::cell_means {

template <int dim>
std::vector<int> cells_at(const CellPoints<dim>& g,
                          const std::vector<Eigen::Matrix<double, dim, 1>>& at) {
  std::vector<Vec2> xy;
  for (const auto& x : g.x) xy.push_back(x.template head<2>());
  const neighbors::PointGrid grid(xy, g.reach);
  std::vector<int> cell;
  for (const auto& x : at) {
    int nearest = -1;
    double best = std::numeric_limits<double>::infinity();
    grid.for_each_within(x.template head<2>(), g.reach, [&](int q) {
      const double d2 = (g.x[q] - x).squaredNorm();
      if (d2 < best || (d2 == best && q < nearest)) best = d2, nearest = q;
    });
    MF_REQUIRE(nearest >= 0, "no Gauss point within ", g.reach, " of (", point_text(x),
               ") to take its cell's mean volumetric strain from");
    cell.push_back(g.cell[nearest]);
  }
  return cell;
}

std::unordered_map<int, std::vector<int>> points_by_cell(const std::vector<int>& cell) {
  std::unordered_map<int, std::vector<int>> members;
  for (int q = 0; q < static_cast<int>(cell.size()); ++q) members[cell[q]].push_back(q);
  return members;
}

template <int dim>
MeanGradients<dim> mean_gradients(const ShapeTableOf<dim>& table,
                                  const std::vector<double>& weight) {
  using Gradient = typename ShapeTableOf<dim>::Gradient;
  std::map<int, Gradient> sum;
  double volume = 0.0;
  for (int r = 0; r < table.rows(); ++r) {
    for (int k = table.offset[r]; k < table.offset[r + 1]; ++k) {
      const auto [it, fresh] = sum.emplace(table.node[k], Gradient::Zero());
      it->second += weight[r] * table.dphi[k];
    }
    volume += weight[r];
  }
  MeanGradients<dim> mean;
  for (const auto& [node, g] : sum) mean.emplace_back(node, g / volume);
  return mean;
}

template <int dim>
ShapeTableOf<dim> widened(const ShapeTableOf<dim>& t, const std::vector<int>& cell,
                          const std::unordered_map<int, MeanGradients<dim>>& means) {
  using Gradient = typename ShapeTableOf<dim>::Gradient;
  ShapeTableOf<dim> out;
  for (int r = 0; r < t.rows(); ++r) {
    std::map<int, std::pair<int, Gradient>> row; // node -> (own entry or -1, mean gradient)
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) row[t.node[k]] = {k, Gradient::Zero()};
    for (const auto& [node, g] : means.at(cell[r])) {
      const auto [it, fresh] = row.emplace(node, std::make_pair(-1, Gradient::Zero()));
      it->second.second = g;
    }
    for (const auto& [node, entry] : row) {
      const auto& [k, mean] = entry;
      out.node.push_back(node);
      out.phi.push_back(k >= 0 ? t.phi[k] : 0.0);
      out.dphi.push_back(k >= 0 ? t.dphi[k] : Gradient::Zero());
      out.volumetric_shift.push_back(mean - out.dphi.back());
    }
    out.offset.push_back(static_cast<int>(out.node.size()));
  }
  return out;
}

#define MF_CELL_MEANS(dim)                                                                         \
  template std::vector<int> cells_at(const CellPoints<dim>&,                                       \
                                     const std::vector<Eigen::Matrix<double, dim, 1>>&);           \
  template MeanGradients<dim> mean_gradients(const ShapeTableOf<dim>&,                             \
                                             const std::vector<double>&);                          \
  template ShapeTableOf<dim> widened(const ShapeTableOf<dim>&, const std::vector<int>&,            \
                                     const std::unordered_map<int, MeanGradients<dim>>&);
MF_CELL_MEANS(2)
MF_CELL_MEANS(3)
#undef MF_CELL_MEANS

} // namespace mf::implicit::cell_means
