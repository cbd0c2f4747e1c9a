#include "meshfree/implicit/galerkin_forms.hpp"
#include "meshfree/core/progress.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>

namespace mf::implicit {

namespace {

void assemble_linear_elastic(const spec::ProblemSpec& spec, const GalerkinModel& m,
                             const std::vector<double>& factors, BlockRows& rows) {
  MF_REQUIRE(factors.size() == spec.galerkin().boundary.size() + 1,
             "assemble_linear_elastic: factors");
  const auto add_matrix = [&](const int* nodes, int n, const double* v) {
    rows.add_matrix(nodes, n, v);
  };
  const auto add_vector = [&](const int* nodes, int n, const double* v) {
    rows.add_vector(nodes, n, v);
  };
  const bool regions = !spec.galerkin().material_regions.empty() || has_gravity(spec);
  const PointLaws laws = regions ? point_laws(spec, domain_rows(m)) : PointLaws{};
  // Each point with the elastic matrix of its material, in the groups that let threads add at
  // once (no shared node in a group).
  const Mat3 C = regions ? Mat3::Zero() : materials::elastic_matrix(spec.elasticity(), spec.model);
  const ShapeTable& t = m.domain_table;
  MF_REQUIRE(m.domain_groups.rows() == t.rows(), "assemble_linear_elastic: points not grouped");
  std::vector<std::vector<double>> K(PointGroups::threads());
  // Progress of large systems: the points done, counted by all threads, reported by thread 0.
  const bool report = 2.0 * m.node_count() >= log::kProgressUnknowns;
  log::PhaseProgress progress("assembly", t.rows(), report);
  m.domain_groups.for_each([&](int r, int thread) {
    const int n = t.offset[r + 1] - t.offset[r];
    K[thread].resize(4 * n * n);
    const Mat3& Cr = regions ? laws.elastic[laws.material.empty() ? 0 : laws.material[r]] : C;
    point_stiffness(t, r, m.domain_weight[r] * Cr, K[thread].data());
    add_matrix(t.node.data() + t.offset[r], n, K[thread].data());
    progress.count_one(thread);
  });
  progress.finish();
  if (has_body_force(spec) && factors.back() != 0.0) {
    std::vector<Vec2> b =
        regions ? laws.body_force
                : std::vector<Vec2>(m.domain_weight.size(), spec.galerkin().body_force);
    for (Vec2& v : b) v *= factors.back();
    add_load(m.domain_table, m.domain_weight, b, add_vector);
  }
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    const ConditionPoints& c = m.conditions[b];
    std::vector<Vec2> values = c.values;
    for (Vec2& v : values) v *= factors[b];
    if (c.bc->constrains)
      add_penalty(c.table, c.weight, c.bc->mask, c.bc->penalty, values, add_matrix, add_vector);
    else
      add_load(c.table, c.weight, values, add_vector);
  }
}

} // namespace

std::unique_ptr<solvers::BlockLinearSystem>
linear_elastic_system(const spec::ProblemSpec& spec, const GalerkinModel& m,
                      const std::vector<double>& factors, const solvers::PetscSession& session) {
  const RowPattern& p = m.pattern;
  return std::make_unique<solvers::BlockLinearSystem>(
      session.comm(), m.node_count(), m.own, p.offset, p.column,
      [&](solvers::BlockValueArrays values, std::vector<double>& rhs) {
        BlockRows rows(p, values);
        assemble_linear_elastic(spec, m, factors, rows);
        rhs = rows.rhs();
      },
      /*spd=*/true, linear_solver_settings(spec, m));
}

BoundaryReport boundary_report(const ConditionPoints& c, const std::vector<double>& d,
                               double factor, const solvers::PetscSession& session) {
  const spec::BoundaryCondition& bc = *c.bc;
  BoundaryReport rep;
  rep.name = bc.name;
  rep.constraint = bc.constrains;
  double force[2] = {0, 0}, gap_max = 0.0;
  for (int k = 0; k < c.table.rows(); ++k) {
    if (!c.mine.counted[k]) continue;
    if (bc.constrains) {
      const Vec2 gap =
          (displacement_at(c.table, k, d) - factor * c.values[k]).cwiseProduct(bc.mask);
      force[0] -= bc.penalty * c.weight[k] * gap.x();
      force[1] -= bc.penalty * c.weight[k] * gap.y();
      gap_max = std::max(gap_max, gap.norm());
    } else {
      force[0] += factor * c.weight[k] * c.values[k].x();
      force[1] += factor * c.weight[k] * c.values[k].y();
    }
  }
  solvers::sum_everywhere(session.comm(), force, 2);
  gap_max = solvers::max_everywhere(session.comm(), gap_max);
  rep.force = Vec2(force[0], force[1]);
  rep.violation_max = gap_max;
  return rep;
}

} // namespace mf::implicit
