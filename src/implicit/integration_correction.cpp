#include "meshfree/implicit/integration_correction.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>

namespace mf::implicit {

void correct_test_gradients(const spec::ProblemSpec& spec, GalerkinModel& m,
                            const solvers::PetscSession& session) {
  const spec::DiscretisationSpec& disc = spec.galerkin().discretisation;
  const int N = m.node_count();
  // Per owned node: the quadrature's sum of grad Psi_I (2), of Psi_I (1), and the boundary
  // integral of Psi_I n (2). Every point whose support holds an owned node is in this rank's
  // table, so the sums of owned nodes are whole here.
  std::vector<double> sums(5 * static_cast<std::size_t>(N), 0.0);
  ShapeTable& t = m.domain_table;
  for (int k = 0; k < t.rows(); ++k) {
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    for (int j = t.offset[k]; j < t.offset[k + 1]; ++j) {
      double* s = sums.data() + 5 * static_cast<std::size_t>(t.node[j]);
      s[0] += w * t.dphi[j].x();
      s[1] += w * t.dphi[j].y();
      s[2] += w * t.phi[j];
    }
  }
  const quadrature::CellSizing sizing{disc.spacing, disc.refinement, disc.cell_size / disc.spacing,
                                      disc.dilation.maxCoeff()};
  const quadrature::BoundaryPoints edge = quadrature::boundary_points(
      spec.domain.boundary(), disc.cell_size, disc.boundary_order, sizing);
  const Csr support = m.space->support_lists(edge.x);
  std::vector<int> rows;
  for (int r = 0; r < support.rows(); ++r)
    if (std::any_of(support.index.begin() + support.offset[r],
                    support.index.begin() + support.offset[r + 1],
                    [&](int I) { return m.own.owns(I); }))
      rows.push_back(r);
  const ShapeTable e = m.space->shape_table(edge.x, rows, support, false);
  for (int k = 0; k < e.rows(); ++k) {
    const Vec2 wn = edge.weight[rows[k]] * edge.normal[rows[k]];
    for (int j = e.offset[k]; j < e.offset[k + 1]; ++j) {
      double* s = sums.data() + 5 * static_cast<std::size_t>(e.node[j]);
      s[3] += e.phi[j] * wn.x();
      s[4] += e.phi[j] * wn.y();
    }
  }
  // xi of the owned nodes, then of every node (the points near a partition boundary hold
  // nodes of other ranks).
  // A node without points is reported after the exchanges, which every rank must reach.
  std::vector<double> xi(2 * static_cast<std::size_t>(N), 0.0);
  int bare = -1;
  for (int I = m.own.begin; I < m.own.end; ++I) {
    const double* s = sums.data() + 5 * static_cast<std::size_t>(I);
    if (!(s[2] > 0.0)) {
      bare = I;
      continue;
    }
    xi[2 * I] = (s[3] - s[0]) / s[2];
    xi[2 * I + 1] = (s[4] - s[1]) / s[2];
  }
  solvers::sum_everywhere(session.comm(), xi.data(), static_cast<int>(xi.size()));
  // Every rank stops, naming the highest such node of any rank.
  bare = static_cast<int>(solvers::max_everywhere(session.comm(), static_cast<double>(bare)));
  // A node whose shape function does not integrate to a positive amount has no point in its
  // support, or a support much smaller than its neighbours' (a spacing that jumps: adapted
  // clouds grade their supports, geometry::grade_spacing).
  if (bare >= 0) {
    const geometry::NodeCloud& c = m.space->nodes();
    fail("VCI: the shape function of node ", bare, " at (", c.x[bare].x(), ", ", c.x[bare].y(),
         "), spacing ", c.spacing[bare],
         ", does not integrate to a positive amount over the body's integration points");
  }
  t.test_dphi.resize(t.dphi.size());
  for (std::size_t j = 0; j < t.dphi.size(); ++j) {
    const int I = t.node[j];
    t.test_dphi[j] = t.dphi[j] + t.phi[j] * Vec2(xi[2 * I], xi[2 * I + 1]);
  }
}

} // namespace mf::implicit
