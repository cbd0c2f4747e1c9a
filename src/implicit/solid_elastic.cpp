#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/nodal_sums.hpp"
#include "meshfree/implicit/solid_elastoplastic_system.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/verification/exact_solutions_3d.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

namespace {

/// Stiffness, penalties, loads and body force of this rank's rows; the body's points in the
/// groups that threads assemble at once.
void assemble(const spec::ProblemSpec& spec, const SolidModel& m, BlockRows& rows) {
  const Mat6 C = elastic_matrix_3d(spec.elasticity());
  const SolidShapeTable& t = m.domain_table;
  const Vec3 b = spec.solid().body_force;
  const int threads = PointGroups::threads();
  std::vector<std::vector<double>> Kt(threads), work(threads), ft(threads);
  m.domain_groups.for_each([&](int r, int thread) {
    const int n = t.offset[r + 1] - t.offset[r];
    const int* nodes = t.node.data() + t.offset[r];
    Kt[thread].resize(9 * static_cast<std::size_t>(n) * n);
    solid_point_stiffness(t, r, m.domain_weight[r] * C, Kt[thread].data(), work[thread]);
    rows.add_matrix(nodes, n, Kt[thread].data());
    if (b.isZero()) return;
    std::vector<double>& f = ft[thread];
    f.resize(3 * n);
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < 3; ++c) f[3 * a + c] = m.domain_weight[r] * t.phi[t.offset[r] + a] * b(c);
    rows.add_vector(nodes, n, f.data());
  });
  std::vector<double> K, f;
  for (const SolidConditionPoints& c : m.conditions) {
    const SolidShapeTable& ct = c.table;
    for (int k = 0; k < ct.rows(); ++k) {
      const int n = ct.offset[k + 1] - ct.offset[k];
      const int* nodes = ct.node.data() + ct.offset[k];
      const double w = c.points.weight[c.mine.rows[k]];
      f.resize(3 * n);
      if (c.bc->constrains) {
        K.resize(9 * static_cast<std::size_t>(n) * n);
        solid_point_penalty(ct, k, c.bc->penalty * w, c.bc->mask, c.values[k], K.data(), f.data());
        rows.add_matrix(nodes, n, K.data());
      } else {
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i) f[3 * a + i] = w * ct.phi[ct.offset[k] + a] * c.values[k](i);
      }
      rows.add_vector(nodes, n, f.data());
    }
  }
}

/// Relative L2 error of u^h and energy error of the strain against the exact solution, over
/// the points this rank counts, summed over the ranks.
void exact_errors(const spec::ProblemSpec& spec, const SolidModel& m, const std::vector<double>& d,
                  const solvers::PetscSession& session, SolidElasticResult& R) {
  const auto& exact = *spec.solid().exact;
  const materials::IsotropicElastic mat = spec.elasticity();
  const Mat6 C = elastic_matrix_3d(mat);
  const Mat6 S = C.inverse();
  double sums[4] = {0, 0, 0, 0}; // |e_u|^2, |u|^2, e_s S e_s, s S s
  for (int r = 0; r < m.domain_table.rows(); ++r) {
    if (!m.domain_mine.counted[r]) continue;
    const Vec3& x = m.domain.x[m.domain_mine.rows[r]];
    const double w = m.domain_weight[r];
    const Vec3 ue = verification::exact_displacement_3d(exact, mat, x);
    const Vec6 se = verification::exact_stress_3d(exact, mat, x);
    const Vec3 eu = solid_displacement_at(m.domain_table, r, d) - ue;
    const Vec6 es = C * solid_strain_at(m.domain_table, r, d) - se;
    sums[0] += w * eu.squaredNorm();
    sums[1] += w * ue.squaredNorm();
    sums[2] += w * es.dot(S * es);
    sums[3] += w * se.dot(S * se);
  }
  solvers::sum_everywhere(session.comm(), sums, 4);
  R.error_l2 = std::sqrt(sums[0] / sums[1]);
  R.error_energy = std::sqrt(sums[2] / sums[3]);
}

} // namespace

SolidElasticResult solve_solid_elastic(const spec::ProblemSpec& spec,
                                       const solvers::PetscSession& session) {
  SolidElasticResult R;
  const SolidModel m = build_solid_model(spec, session, R.timer);
  const int N = m.node_count();
  R.counts = count_model(spec, m);
  std::unique_ptr<solvers::BlockLinearSystem> system;
  {
    PhaseTimer::Scope scope(R.timer, "assembly");
    system = std::make_unique<solvers::BlockLinearSystem>(
        session.comm(), N, m.own, m.pattern.offset, m.pattern.column,
        [&](solvers::BlockValueArrays values, std::vector<double>& rhs) {
          BlockRows rows(m.pattern, values, 3);
          assemble(spec, m, rows);
          rhs = rows.rhs();
        },
        /*spd=*/!spec.solid().discretisation.vci, solid_solver_settings(spec, m), 3);
  }
  {
    PhaseTimer::Scope scope(R.timer, "solve");
    R.solve = system->solve();
    R.parameters = system->solution_everywhere();
    R.matrix_nonzeros = system->global_nonzeros();
  }
  log::info("solved with ", R.solve.solver, ": ", R.solve.reason_name, ", ", R.solve.iterations,
            " iterations, relative residual ", R.solve.residual_norm);
  for (double v : R.parameters)
    MF_REQUIRE(std::isfinite(v), "the solution contains NaN or Inf: the system is singular; "
                                 "check the boundary conditions");
  PhaseTimer::Scope scope(R.timer, "postprocess");
  for (const auto& c : m.conditions)
    R.boundary.push_back(face_report(c, R.parameters, 1.0, session));
  if (spec.solid().exact) exact_errors(spec, m, R.parameters, session, R);
  R.node_x = m.node_positions();
  R.node_u = nodal_displacements(m, R.parameters);
  std::vector<Vec3> at;
  for (const spec::GaugeSpec& g : spec.solid().gauges) at.push_back(g.at);
  R.gauge_u = gauge_displacements(solid_shapes_at(m, at), m.own, R.parameters, session);
  const Mat6 C = elastic_matrix_3d(spec.elasticity());
  R.node_stress = nodal_averages<6>(m, session, [&](int k, double* v) {
    const Vec6 stress = C * solid_strain_at(m.domain_table, k, R.parameters);
    std::copy(stress.data(), stress.data() + 6, v);
  });
  auto lines = std::make_shared<SolidLineSampler>(spec, m, solid_material_law(spec));
  if (session.rank() == 0) lines->record(1, R.parameters);
  R.lines = lines;
  R.memory = solvers::peak_memory(session.comm());
  return R;
}

} // namespace mf::implicit
