#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/load_stepping.hpp"
#include "meshfree/implicit/nodal_sums.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/implicit/solid_elastoplastic_system.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include <algorithm>
#include <memory>

namespace mf::implicit {

namespace {

/// The schedule of a 3D problem: its steps, and the conditions whose factor moves the body.
ScheduleSpec solid_schedule(const spec::ProblemSpec& spec) {
  const spec::SolidSpec& s = spec.solid();
  ScheduleSpec out;
  out.steps = &s.steps;
  out.nonlinear = s.nonlinear;
  out.fields_every = s.fields_every;
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

/// The field series of the run (rank 0 writes): u^h, and the stress and equivalent plastic strain
/// averaged at the nodes (nodal_sums.hpp), in fields.h5, and the stress and equivalent plastic
/// strain at every Gauss point once (gauss_points.h5), at the increments the
/// schedule marks for output, at time step + step fraction.
class SolidSeries {
public:
  SolidSeries(const SolidModel& m, const solvers::PetscSession& session, io::OutputDirectory* out)
      : m_(m), session_(session) {
    const std::vector<double> points = solvers::gather_on_root(session.comm(), counted_positions());
    std::vector<double> nodes;
    for (const Vec3& x : m.node_positions()) nodes.insert(nodes.end(), {x.x(), x.y(), x.z()});
    fields_ = std::make_unique<io::FieldOutput>(out, "fields", nodes);
    fields_->vector("displacement", [this](std::vector<double>& v) { v = node_u_; });
    add_node_stress_fields(*fields_, node_values_, 7);
    points_ = std::make_unique<io::FieldOutput>(out, "gauss_points", points);
    add_node_stress_fields(*points_, values_, 7); // the same fields, at the Gauss points
  }

  /// Collective: `all` is the whole d on rank 0 (empty elsewhere).
  void write(double time, const SolidElastoplasticSystem& system, const std::vector<double>& all) {
    std::vector<double> mine;
    const SolidPointStates& s = system.states();
    for (std::size_t k = 0; k < s.committed.size(); ++k) {
      if (!m_.domain_mine.counted[k]) continue;
      for (int c = 0; c < 6; ++c) mine.push_back(s.committed_stress[k](c));
      mine.push_back(s.committed[k].alpha);
    }
    values_ = solvers::gather_on_root(session_.comm(), mine);
    node_values_ = nodal_averages<7>(m_, session_, [&s](int k, double* v) {
      for (int c = 0; c < 6; ++c) v[c] = s.committed_stress[k](c);
      v[6] = s.committed[k].alpha;
    });
    if (session_.rank() != 0) return;
    node_u_.clear();
    for (const Vec3& u : nodal_displacements(m_, all))
      node_u_.insert(node_u_.end(), {u.x(), u.y(), u.z()});
    fields_->write(time);
    points_->write(time);
  }

  void close() {
    fields_->close();
    points_->close();
  }

private:
  std::vector<double> counted_positions() const {
    std::vector<double> x;
    for (std::size_t k = 0; k < m_.domain_mine.rows.size(); ++k)
      if (m_.domain_mine.counted[k]) {
        const Vec3& p = m_.domain.x[m_.domain_mine.rows[k]];
        x.insert(x.end(), {p.x(), p.y(), p.z()});
      }
    return x;
  }

  const SolidModel& m_;
  const solvers::PetscSession& session_;
  std::unique_ptr<io::FieldOutput> fields_, points_;
  std::vector<double> node_u_, values_;
  std::vector<double> node_values_; // the stress and plastic strain averaged at the nodes
};

} // namespace

SolidElastoplasticResult solve_solid_elastoplastic(const spec::ProblemSpec& spec,
                                                   const solvers::PetscSession& session,
                                                   io::OutputDirectory* out) {
  SolidElastoplasticResult R;
  R.model = std::make_shared<const SolidModel>(build_solid_model(spec, session, R.timer));
  const SolidModel& m = *R.model;
  R.material = solid_material_law(spec);
  const int N = m.node_count();
  R.counts = count_model(spec, m);
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
  SolidSeries series(m, session, out);
  series.write(0.0, system, newton.gather_on_root(d));
  auto lines = std::make_shared<SolidLineSampler>(spec, m, R.material);
  if (session.rank() == 0 && spec.solid().samples()) lines->record(0, d);
  SchedulePosition at;
  const ScheduleOutcome o = run_load_schedule(
      solid_schedule(spec), system, newton, d,
      [&](IncrementRecord rec, bool write_fields) -> const IncrementRecord& {
        PhaseTimer::Scope scope(R.timer, "increment_output");
        SolidIncrement inc;
        inc.record = std::move(rec);
        describe_increment(m, system, gauges, d, session, inc);
        if (spec.solid().record_increment_parameters) {
          inc.record.parameters = newton.gather_on_root(d);
          solvers::broadcast(session.comm(), inc.record.parameters, 0);
        }
        if (write_fields)
          series.write(inc.record.step + inc.record.step_fraction, system,
                       newton.gather_on_root(d));
        if (spec.solid().samples()) { // collective: every rank gathers, rank 0 samples
          const std::vector<double> all = newton.gather_on_root(d);
          if (session.rank() == 0) lines->record(static_cast<int>(R.increments.size()), all);
        }
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
  R.lines = lines;
  series.close();
  R.memory = solvers::peak_memory(session.comm());
  return R;
}

} // namespace mf::implicit
