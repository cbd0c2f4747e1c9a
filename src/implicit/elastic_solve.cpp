#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>
#include <cmath>
#include <tuple>

namespace mf::implicit {

namespace {

/// Fields at arbitrary points (nodes, line samples): u^h, stress, szz.
void evaluate_fields(const GalerkinModel& m, const spec::ProblemSpec& spec,
                     const std::vector<Vec2>& x, const std::vector<double>& d, std::vector<Vec2>& u,
                     std::vector<Vec3>& stress, std::vector<double>& szz) {
  const ShapeTable t = shapes_at(m, x, true);
  const PointLaws laws = point_laws(spec, x); // the material of each point
  u.resize(x.size());
  stress.resize(x.size());
  szz.resize(x.size());
  for (int r = 0; r < t.rows(); ++r) {
    u[r] = displacement_at(t, r, d);
    std::tie(stress[r], szz[r]) = laws.elastic_stress(spec.model, r, strain_at(t, r, d));
  }
}

} // namespace

namespace {

/// Relative L2 and energy-norm errors against the exact solution, over the whole body.
std::pair<double, double> exact_errors(const spec::ProblemSpec& spec, const GalerkinModel& m,
                                       const std::vector<double>& d,
                                       const solvers::PetscSession& session) {
  const Mat3 C = materials::elastic_matrix(spec.elasticity(), spec.model);
  const Mat3 Cinv = C.inverse();
  const materials::IsotropicElastic exact_mat =
      materials::plane_stress_equivalent(spec.elasticity(), spec.model);
  double sums[4] = {0, 0, 0, 0}; // |e_u|^2, |u|^2, e_eps.C.e_eps, eps.C.eps
  for (int k = 0; k < m.domain_table.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    const Vec2& x = m.domain.x[m.domain_mine.rows[k]];
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    const Vec2 ue = verification::exact_displacement(*spec.galerkin().exact, exact_mat, x);
    const Vec3 ee = Cinv * verification::exact_stress(*spec.galerkin().exact, exact_mat, x);
    const Vec2 eu = displacement_at(m.domain_table, k, d) - ue;
    const Vec3 eps = strain_at(m.domain_table, k, d) - ee;
    sums[0] += w * eu.squaredNorm();
    sums[1] += w * ue.squaredNorm();
    sums[2] += w * eps.dot(C * eps);
    sums[3] += w * ee.dot(C * ee);
  }
  solvers::sum_everywhere(session.comm(), sums, 4);
  return {std::sqrt(sums[0] / sums[1]), std::sqrt(sums[2] / sums[3])};
}

/// The recovery estimate of the solution's stress at this rank's Gauss points.
ErrorEstimate elastic_estimate(const spec::ProblemSpec& spec, const GalerkinModel& m,
                               const std::vector<double>& d, const solvers::PetscSession& session) {
  const PointLaws laws = point_laws(spec, domain_rows(m));
  std::vector<Vec3> stress(m.domain_table.rows());
  for (int k = 0; k < m.domain_table.rows(); ++k)
    stress[k] = laws.elastic_stress(spec.model, k, strain_at(m.domain_table, k, d)).first;
  const Mat3 C = materials::elastic_matrix(spec.elasticity(), spec.model);
  return recovery_error(m, stress, C.inverse(), session);
}

/// u^h and stresses at the nodes and along the sample lines, u^h at the gauges (on the calling
/// rank).
void sample_fields(const spec::ProblemSpec& spec, const GalerkinModel& m, ElasticResult& R) {
  const auto& d = R.parameters;
  R.node_x = m.node_positions();
  evaluate_fields(m, spec, R.node_x, d, R.node_u, R.node_stress, R.node_szz);
  if (!spec.galerkin().gauges.empty()) {
    std::vector<Vec2> at;
    for (const spec::GaugeSpec& g : spec.galerkin().gauges) at.push_back(g.at.head<2>());
    std::vector<Vec3> stress;
    std::vector<double> szz;
    evaluate_fields(m, spec, at, d, R.gauge_u, stress, szz);
  }
  for (const auto& line : spec.galerkin().lines) {
    LineSample s;
    for (int k = 0; k < line.points; ++k) {
      const double f = static_cast<double>(k) / (line.points - 1);
      const Vec2 x = line.from + f * (line.to - line.from);
      if (!spec.domain.contains(x, 1e-9)) continue;
      s.x.push_back(x);
      s.s.push_back(f * (line.to - line.from).norm());
    }
    std::vector<double> szz;
    evaluate_fields(m, spec, s.x, d, s.u, s.stress, szz);
    R.lines.emplace_back(line.name, std::move(s));
  }
}

} // namespace

ElasticResult solve_elastic_static(const spec::ProblemSpec& spec,
                                   const solvers::PetscSession& session, bool display) {
  ElasticResult R;
  const GalerkinModel m = build_galerkin_model(spec, session, R.timer);
  R.nodes = m.node_count();
  R.dofs = 2 * R.nodes;
  R.domain_points = static_cast<int>(m.domain.x.size());
  R.cells = m.domain.cell_count;
  for (const auto& c : m.conditions) R.boundary_points += static_cast<int>(c.points.x.size());
  R.mean_support =
      static_cast<double>(m.domain_support.index.size()) / std::max(1, m.domain_support.rows());
  log::info("integration: ", R.cells, " background cells, ", R.domain_points, " domain points, ",
            R.boundary_points, " boundary points");

  std::unique_ptr<solvers::BlockLinearSystem> system;
  {
    PhaseTimer::Scope scope(R.timer, "assembly");
    system = linear_elastic_system(
        spec, m, std::vector<double>(spec.galerkin().boundary.size() + 1, 1.0), session);
  }
  R.matrix_nonzeros = system->global_nonzeros();
  log::info("matrix: ", R.dofs, " x ", R.dofs, ", ", static_cast<long>(R.matrix_nonzeros),
            " nonzeros");
  {
    PhaseTimer::Scope scope(R.timer, "solve");
    R.solve = system->solve();
    R.parameters = system->solution_everywhere();
  }
  log::info("solved with ", R.solve.solver, ": ", R.solve.reason_name, ", relative residual ",
            R.solve.residual_norm);
  for (double v : R.parameters)
    MF_REQUIRE(std::isfinite(v), "the solution contains NaN or Inf: the system is singular; "
                                 "check the boundary conditions");

  PhaseTimer::Scope scope(R.timer, "postprocess");
  if (spec.galerkin().discretisation.adapt)
    R.estimate = elastic_estimate(spec, m, R.parameters, session);
  if (spec.galerkin().exact)
    std::tie(R.error_l2, R.error_energy) = exact_errors(spec, m, R.parameters, session);
  for (const auto& c : m.conditions) {
    R.boundary.push_back(boundary_report(c, R.parameters, 1.0, session));
    R.violation_max = std::max(R.violation_max, R.boundary.back().violation_max);
  }
  if (display)
    std::tie(R.display_mesh, R.display) = elastic_display(spec, m, R.parameters, session);
  session.collective([&] {
    if (session.rank() != 0) return;
    sample_fields(spec, m, R);
    R.output_cells = output_cells(m);
    double umax = 0.0;
    for (const auto& u : R.node_u) umax = std::max(umax, u.norm());
    R.violation_relative = umax > 0.0 ? R.violation_max / umax : 0.0;
  });
  R.memory = solvers::peak_memory(session.comm());
  return R;
}

} // namespace mf::implicit
