#include "meshfree/app/galerkin_model.hpp"
#include "meshfree/app/elastic_static.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include <algorithm>

namespace mf::app {

namespace {

RankPoints rank_points(const implicit::Csr& support, solvers::OwnedRange own, int node_count,
                       const solvers::PetscSession& s) {
  RankPoints p;
  for (int r = 0; r < support.rows(); ++r) {
    const int* first = support.index.data() + support.offset[r];
    const int* last = support.index.data() + support.offset[r + 1];
    if (std::any_of(first, last, [&](int I) { return own.owns(I); })) {
      p.rows.push_back(r);
      // support lists are sorted, so the lowest node is the first one
      p.counted.push_back(solvers::owner_of(*first, node_count, s.size()) == s.rank());
    }
  }
  return p;
}

/// Traction sigma . n from Voigt stress [sxx, syy, sxy].
Vec2 traction(const Vec3& s, const Vec2& n) {
  return {s(0) * n.x() + s(2) * n.y(), s(2) * n.x() + s(1) * n.y()};
}

/// Prescribed displacement or traction at the given rows of a condition's points.
std::vector<Vec2> condition_values(const io::ProblemSpec& spec, const io::BoundaryCondition& bc,
                                   const quadrature::BoundaryPoints& pts,
                                   const std::vector<int>& rows) {
  const materials::IsotropicElastic m =
      materials::plane_stress_equivalent(spec.material, spec.model);
  std::vector<Vec2> out;
  for (int r : rows) {
    if (bc.constrains)
      out.push_back(bc.value_from_exact ? verification::exact_displacement(*spec.exact, m, pts.x[r])
                                        : bc.value);
    else
      out.push_back(
          bc.traction_from_exact
              ? traction(verification::exact_stress(*spec.exact, m, pts.x[r]), pts.normal[r])
              : bc.traction);
  }
  return out;
}

void require_covered(const implicit::Csr& support, const std::vector<Vec2>& x) {
  for (int r = 0; r < support.rows(); ++r)
    MF_REQUIRE(support.size(r) > 0, "integration point (", x[r].x(), ", ", x[r].y(),
               ") is covered by no node: raise discretisation.dilation");
}

} // namespace

GalerkinModel build_galerkin_model(const io::ProblemSpec& spec,
                                   const solvers::PetscSession& session, PhaseTimer& timer) {
  const io::DiscretisationSpec& disc = spec.discretisation;
  GalerkinModel m;
  {
    PhaseTimer::Scope scope(timer, "nodes");
    m.space = std::make_unique<implicit::MeshfreeSpace>(
        geometry::generate_nodes(spec.domain, disc.spacing, disc.refinement), disc.shape,
        disc.dilation);
  }
  const int N = m.node_count();
  log::info("nodes: ", N, " (", 2 * N, " DOFs), ", describe_method(disc));

  // Integration points: background cells over the body (refined with the nodes), Gauss points
  // on the loaded and constrained boundary pieces.
  m.conditions.resize(spec.boundary.size());
  {
    PhaseTimer::Scope scope(timer, "quadrature");
    const quadrature::CellSizing sizing{disc.spacing, disc.refinement,
                                        disc.cell_size / disc.spacing, disc.dilation.maxCoeff()};
    m.domain =
        quadrature::domain_points(spec.domain, disc.cell_size, disc.order, disc.cut_levels, sizing);
    for (std::size_t b = 0; b < spec.boundary.size(); ++b) {
      const io::BoundaryCondition& bc = spec.boundary[b];
      m.conditions[b].bc = &bc;
      m.conditions[b].points =
          quadrature::boundary_points(io::select_boundary(spec.domain, bc.on, bc.key_path),
                                      disc.cell_size, disc.boundary_order, sizing);
    }
  }

  // Neighbours: support lists of every point, the points this rank integrates, and the exact
  // pattern of its block rows.
  m.own = solvers::owned_nodes(N, session.rank(), session.size());
  {
    PhaseTimer::Scope scope(timer, "neighbours");
    m.domain_support = m.space->support_lists(m.domain.x);
    require_covered(m.domain_support, m.domain.x);
    std::vector<const implicit::Csr*> coupling{&m.domain_support};
    for (auto& c : m.conditions) {
      c.support = m.space->support_lists(c.points.x);
      require_covered(c.support, c.points.x);
      if (c.bc->constrains) coupling.push_back(&c.support);
      c.mine = rank_points(c.support, m.own, N, session);
    }
    m.domain_mine = rank_points(m.domain_support, m.own, N, session);
    m.pattern = implicit::coupling_pattern(coupling, N, m.own.begin, m.own.end);
  }

  // Shape functions at this rank's points, and what each point carries.
  {
    PhaseTimer::Scope scope(timer, "shape_functions");
    session.collective([&] {
      m.domain_table = m.space->shape_table(m.domain.x, m.domain_mine.rows, m.domain_support, true);
      for (auto& c : m.conditions)
        c.table = m.space->shape_table(c.points.x, c.mine.rows, c.support, false);
    });
    for (int r : m.domain_mine.rows) m.domain_weight.push_back(m.domain.weight[r] * spec.thickness);
    for (auto& c : m.conditions) {
      for (int r : c.mine.rows) c.weight.push_back(c.points.weight[r] * spec.thickness);
      c.values = condition_values(spec, *c.bc, c.points, c.mine.rows);
    }
  }
  return m;
}

} // namespace mf::app

namespace mf::app {

implicit::ShapeTable shapes_at(const GalerkinModel& m, const std::vector<Vec2>& x, bool gradients) {
  const implicit::Csr support = m.space->support_lists(x);
  require_covered(support, x);
  std::vector<int> all(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) all[i] = static_cast<int>(i);
  return m.space->shape_table(x, all, support, gradients);
}

implicit::BlockRows assemble_linear_elastic(const io::ProblemSpec& spec, const GalerkinModel& m,
                                            const std::vector<double>& factors) {
  MF_REQUIRE(factors.size() == spec.boundary.size() + 1, "assemble_linear_elastic: factors");
  implicit::BlockRows rows(m.pattern);
  const auto add_matrix = [&](const int* nodes, int n, const double* v) {
    rows.add_matrix(nodes, n, v);
  };
  const auto add_vector = [&](const int* nodes, int n, const double* v) {
    rows.add_vector(nodes, n, v);
  };
  implicit::add_stiffness(m.domain_table, m.domain_weight,
                          materials::elastic_matrix(spec.material, spec.model), add_matrix);
  if (!spec.body_force.isZero() && factors.back() != 0.0)
    implicit::add_load(m.domain_table, m.domain_weight,
                       std::vector<Vec2>(m.domain_weight.size(), factors.back() * spec.body_force),
                       add_vector);
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    const ConditionPoints& c = m.conditions[b];
    std::vector<Vec2> values = c.values;
    for (Vec2& v : values) v *= factors[b];
    if (c.bc->constrains)
      implicit::add_penalty(c.table, c.weight, c.bc->mask, c.bc->penalty, values, add_matrix,
                            add_vector);
    else
      implicit::add_load(c.table, c.weight, values, add_vector);
  }
  return rows;
}

BoundaryReport boundary_report(const ConditionPoints& c, const std::vector<double>& d,
                               double factor, const solvers::PetscSession& session) {
  const io::BoundaryCondition& bc = *c.bc;
  BoundaryReport rep;
  rep.name = bc.name;
  rep.constraint = bc.constrains;
  double force[2] = {0, 0}, gap_max = 0.0;
  for (int k = 0; k < c.table.rows(); ++k) {
    if (!c.mine.counted[k]) continue;
    if (bc.constrains) {
      const Vec2 gap =
          (implicit::displacement_at(c.table, k, d) - factor * c.values[k]).cwiseProduct(bc.mask);
      force[0] -= bc.penalty * c.weight[k] * gap.x();
      force[1] -= bc.penalty * c.weight[k] * gap.y();
      gap_max = std::max(gap_max, gap.norm());
    } else {
      force[0] += factor * c.weight[k] * c.values[k].x();
      force[1] += factor * c.weight[k] * c.values[k].y();
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, force, 2, MPI_DOUBLE, MPI_SUM, session.comm());
  MPI_Allreduce(MPI_IN_PLACE, &gap_max, 1, MPI_DOUBLE, MPI_MAX, session.comm());
  rep.force = Vec2(force[0], force[1]);
  rep.violation_max = gap_max;
  return rep;
}

} // namespace mf::app
