#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/load_stepping.hpp"
#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/implicit/solid_elastoplastic_system.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include <algorithm>

namespace mf::implicit {

namespace {

/// The schedule of a 3D problem: its steps, and the conditions whose factor moves the body.
ScheduleSpec solid_schedule(const spec::ProblemSpec& spec) {
  const spec::SolidSpec& s = spec.solid();
  ScheduleSpec out;
  out.steps = &s.steps;
  out.nonlinear = s.nonlinear;
  for (const spec::FaceCondition& bc : s.boundary) {
    const bool drives = bc.value_from_exact || bc.traction_from_exact ||
                        (bc.constrains      ? !bc.value.cwiseProduct(bc.mask).isZero()
                         : bc.pressure_load ? bc.pressure != 0.0
                                            : !bc.traction.isZero());
    out.driving.push_back(drives ? bc.name : std::string());
  }
  out.body_force = !s.body_force.isZero();
  return out;
}

/// u^h at the gauges: each rank sums its owned nodes' terms (the owned entries of d are always
/// the current ones), then the ranks add them up.
std::vector<Vec3> gauge_displacements(const SolidShapeTable& t, const solvers::OwnedRange& own,
                                      const std::vector<double>& d,
                                      const solvers::PetscSession& session) {
  std::vector<double> u(3 * static_cast<std::size_t>(t.rows()), 0.0);
  for (int g = 0; g < t.rows(); ++g)
    for (int k = t.offset[g]; k < t.offset[g + 1]; ++k)
      if (own.owns(t.node[k]))
        for (int c = 0; c < 3; ++c) u[3 * g + c] += t.phi[k] * d[3 * t.node[k] + c];
  solvers::sum_everywhere(session.comm(), u.data(), static_cast<int>(u.size()));
  std::vector<Vec3> out;
  for (int g = 0; g < t.rows(); ++g) out.emplace_back(u[3 * g], u[3 * g + 1], u[3 * g + 2]);
  return out;
}

/// The increment's faces, gauges, plastic points and largest equivalent plastic strain.
void describe_increment(const SolidModel& m, const SolidElastoplasticSystem& system,
                        const SolidShapeTable& gauges, const std::vector<double>& d,
                        const solvers::PetscSession& session, SolidIncrement& inc) {
  inc.gauges = gauge_displacements(gauges, m.own, d, session);
  const std::vector<double>& f = inc.record.factors;
  for (std::size_t c = 0; c < m.conditions.size(); ++c)
    inc.faces.push_back(face_report(m.conditions[c], d, f.empty() ? 0.0 : f[c], session));
  long plastic = 0;
  double alpha = 0.0;
  const SolidPointStates& s = system.states();
  for (std::size_t k = 0; k < s.committed.size(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    plastic += s.committed[k].alpha > 0.0;
    alpha = std::max(alpha, s.committed[k].alpha);
  }
  inc.record.plastic_points = solvers::sum_everywhere(session.comm(), plastic);
  inc.record.max_plastic_strain = solvers::max_everywhere(session.comm(), alpha);
}

/// The Gauss points each counted once, on rank 0.
void gather_points(const SolidModel& m, const SolidElastoplasticSystem& system,
                   const solvers::PetscSession& session, SolidElastoplasticResult& R) {
  std::vector<double> mine;
  const SolidPointStates& s = system.states();
  for (std::size_t k = 0; k < s.committed.size(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    const Vec3& x = m.domain.x[m.domain_mine.rows[k]];
    mine.insert(mine.end(), {x.x(), x.y(), x.z()});
    for (int c = 0; c < 6; ++c) mine.push_back(s.committed_stress[k](c));
    mine.push_back(s.committed[k].alpha);
  }
  const std::vector<double> all = solvers::gather_on_root(session.comm(), mine);
  for (std::size_t i = 0; i + 10 <= all.size(); i += 10) {
    R.point_x.emplace_back(all[i], all[i + 1], all[i + 2]);
    Vec6 sig;
    for (int c = 0; c < 6; ++c) sig(c) = all[i + 3 + c];
    R.point_stress.push_back(sig);
    R.point_plastic_strain.push_back(all[i + 9]);
  }
}

} // namespace

SolidElastoplasticResult solve_solid_elastoplastic(const spec::ProblemSpec& spec,
                                                   const solvers::PetscSession& session) {
  SolidElastoplasticResult R;
  const SolidModel m = build_solid_model(spec, session, R.timer);
  const int N = m.node_count();
  R.nodes = N;
  R.dofs = 3 * N;
  R.domain_points = static_cast<int>(m.domain.x.size());
  for (const auto& c : m.conditions) R.boundary_points += static_cast<int>(c.points.x.size());
  log::info(describe_solid_method(spec), ": ", N, " nodes, ", R.dofs, " DOFs, ", R.domain_points,
            " domain points, ", R.boundary_points, " boundary points");
  SolidElastoplasticSystem system(spec, m);
  solvers::NonlinearBlockSystem newton(
      session.comm(), N, m.own, m.pattern.offset, m.pattern.column, system.needed_nodes(),
      [&](const std::vector<double>& d, double* r, solvers::ResidualSums& sums) {
        system.residual(d, r, sums);
      },
      [&](const std::vector<double>& d, solvers::BlockValueArrays v) { system.jacobian(d, v); },
      solid_solver_settings(spec, m), 3);
  R.solver = newton.description();
  std::vector<double> d(3 * static_cast<std::size_t>(N), 0.0);
  SolidIncrement unloaded;
  unloaded.record.factors.assign(spec.solid().boundary.size() + 1, 0.0);
  std::vector<Vec3> at_gauges;
  for (const spec::GaugeSpec& g : spec.solid().gauges) at_gauges.push_back(g.at);
  const SolidShapeTable gauges = solid_shapes_at(m, at_gauges);
  describe_increment(m, system, gauges, d, session, unloaded);
  R.increments.push_back(unloaded);
  SchedulePosition at;
  const ScheduleOutcome o = run_load_schedule(
      solid_schedule(spec), system, newton, d,
      [&](IncrementRecord rec, bool) -> const IncrementRecord& {
        PhaseTimer::Scope scope(R.timer, "increment_output");
        SolidIncrement inc;
        inc.record = std::move(rec);
        describe_increment(m, system, gauges, d, session, inc);
        R.increments.push_back(std::move(inc));
        return R.increments.back().record;
      },
      at);
  R.status = o.status;
  R.stop_reason = o.stop_reason;
  R.timer.add("newton", o.newton_seconds);
  PhaseTimer::Scope scope(R.timer, "postprocess");
  R.parameters = newton.gather_on_root(d);
  solvers::broadcast(session.comm(), R.parameters, 0);
  R.node_x = m.node_positions();
  R.node_u = nodal_displacements(m, R.parameters);
  gather_points(m, system, session, R);
  R.memory = solvers::peak_memory(session.comm());
  return R;
}

} // namespace mf::implicit
