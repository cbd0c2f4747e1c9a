#include "meshfree/implicit/increment_recorder.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/galerkin_forms.hpp"
#include "meshfree/implicit/nodal_average.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>

namespace mf::implicit {

/// Gauss-point fields of the counted points, gathered on rank 0 in rank order, for the
/// gauss_points series.
struct IncrementRecorder::GaussOutput {
  std::vector<int> counted_rows; // table rows of this rank's counted points
  std::vector<double> values[7]; // gathered, on rank 0
  std::unique_ptr<io::FieldOutput> series;

  GaussOutput(const GalerkinModel& m, const solvers::PetscSession& session,
              io::OutputDirectory* out) {
    series = std::make_unique<io::FieldOutput>(out, "gauss_points", counted_points(m, session));
    const char* names[] = {"stress_xx", "stress_yy",      "stress_xy", "stress_zz",
                           "von_mises", "plastic_strain", "plastic"};
    for (int f = 0; f < 7; ++f) series->scalar(names[f], values[f]);
  }

  /// The steps from now on are on the points of model m.
  void move_to(const GalerkinModel& m, const solvers::PetscSession& session) {
    series->regrid(counted_points(m, session));
  }

  /// The counted points of m (counted_rows, this rank's table rows), gathered on rank 0.
  std::vector<Vec2> counted_points(const GalerkinModel& m, const solvers::PetscSession& session) {
    counted_rows.clear();
    std::vector<double> x;
    for (int k = 0; k < m.domain_table.rows(); ++k)
      if (m.domain_mine.counted[k]) {
        counted_rows.push_back(k);
        const Vec2& p = m.domain.x[m.domain_mine.rows[k]];
        x.push_back(p.x());
        x.push_back(p.y());
      }
    const std::vector<double> all = solvers::gather_on_root(session.comm(), x);
    std::vector<Vec2> points(all.size() / 2);
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = Vec2(all[2 * i], all[2 * i + 1]);
    return points;
  }

  void write(double time, const PointStates& st, const solvers::PetscSession& session) {
    for (int f = 0; f < 7; ++f) {
      std::vector<double> v;
      for (int k : counted_rows) {
        const Vec3& s = st.stress[k];
        const double value[] = {s(0),
                                s(1),
                                s(2),
                                st.stress_zz[k],
                                materials::von_mises(s, st.stress_zz[k]),
                                st.committed[k].alpha,
                                static_cast<double>(st.plastic[k])};
        v.push_back(value[f]);
      }
      values[f] = solvers::gather_on_root(session.comm(), v);
    }
    series->write(time);
  }
};

IncrementRecorder::IncrementRecorder(const spec::ProblemSpec& spec, const GalerkinModel& m,
                                     const solvers::PetscSession& session, io::OutputDirectory* out)
    : spec_(&spec), m_(&m), session_(session), writes_(out != nullptr) {
  const bool root = session.rank() == 0;
  make_tables(spec, m);
  session.collective([&] {
    if (root)
      fields_ =
          std::make_unique<io::FieldOutput>(out, "fields", m.node_positions(), output_cells(m));
  });
  display_ = std::make_unique<DisplaySeries>(root ? out : nullptr, display_mesh_);
  if (!fields_) fields_ = std::make_unique<io::FieldOutput>(nullptr, "fields", std::vector<Vec2>{});
  fields_->vector2("displacement", [this](std::vector<Vec2>& v) { v = node_u_; });
  fields_->vector2("nodal_parameters", [this](std::vector<Vec2>& v) { v = node_parameters_; });
  const char* names[] = {"stress_xx", "stress_yy",      "stress_xy",       "stress_zz",
                         "von_mises", "plastic_strain", "plastic_fraction"};
  for (int f = 0; f < 7; ++f) fields_->scalar(names[f], node_values_[f]);
  gauss_ = std::make_unique<GaussOutput>(m, session, root ? out : nullptr);
}

void IncrementRecorder::make_tables(const spec::ProblemSpec& spec, const GalerkinModel& m) {
  const solvers::PetscSession& session = session_;
  const bool root = session.rank() == 0;
  session.collective([&] {
    if (!root) return;
    node_table_ = shapes_at(m, m.node_positions(), false);
    std::vector<Vec2> mx;
    for (const auto& mon : spec.galerkin().gauges) mx.push_back(mon.at.head<2>());
    if (!mx.empty()) monitor_table_ = shapes_at(m, mx, false);
    line_tables_.clear();
    line_points_.clear();
    for (const auto& line : spec.galerkin().lines) {
      std::vector<Vec2> x;
      for (int k = 0; k < line.points; ++k) {
        const Vec2 p =
            line.from + (line.to - line.from) * (static_cast<double>(k) / (line.points - 1));
        if (spec.domain.contains(p, 1e-9)) x.push_back(p);
      }
      line_tables_.push_back(shapes_at(m, x, false));
      line_points_.emplace_back(&line, std::move(x));
    }
    if (writes_) display_mesh_ = display_mesh(spec, m);
  });
  if (has_gravity(spec)) {
    // The body force over the body at factor 1: sum of w b over the counted points.
    double f[2] = {0.0, 0.0};
    for (int k = 0; k < m.domain_table.rows(); ++k) {
      if (!m.domain_mine.counted[k]) continue;
      const int r = m.domain_mine.rows[k];
      const Vec2 b = body_force_at(spec, m.domain.x[r]) * (m.domain.weight[r] * spec.thickness);
      f[0] += b.x();
      f[1] += b.y();
    }
    solvers::sum_everywhere(session.comm(), f, 2);
    body_load_ = Vec2(f[0], f[1]);
  }
}

void IncrementRecorder::move_to(const spec::ProblemSpec& spec, const GalerkinModel& m) {
  spec_ = &spec;
  m_ = &m;
  make_tables(spec, m);
  if (session_.rank() == 0) {
    fields_->regrid(m.node_positions(), output_cells(m));
    display_->regrid(display_mesh_);
  }
  gauss_->move_to(m, session_);
}

IncrementRecorder::~IncrementRecorder() = default;

void IncrementRecorder::record(IncrementRecord rec, const std::vector<double>& d,
                               const PointStates& st, const solvers::NonlinearBlockSystem& newton,
                               bool write_fields, ElastoplasticResult& R) {
  const GalerkinModel& m = *m_;
  const spec::ProblemSpec& spec = *spec_;
  const solvers::PetscSession& session = session_;
  const bool root = session.rank() == 0;
  if (R.lines.size() != line_points_.size())
    for (const auto& [line, x] : line_points_)
      R.lines.emplace_back(line->name, std::vector<std::vector<double>>{});

  rec.boundary.clear();
  for (std::size_t b = 0; b < m.conditions.size(); ++b)
    rec.boundary.push_back(boundary_report(m.conditions[b], d, rec.factors[b], session));
  double alpha_max = 0.0, body_area = 0.0;
  long plastic = 0;
  for (int k = 0; k < m.domain_table.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    alpha_max = std::max(alpha_max, st.committed[k].alpha);
    plastic += st.plastic[k];
    body_area += m.domain.weight[m.domain_mine.rows[k]];
  }
  rec.max_plastic_strain = solvers::max_everywhere(session.comm(), alpha_max);
  rec.plastic_points = solvers::sum_everywhere(session.comm(), plastic);
  body_area = solvers::sum_everywhere(session.comm(), body_area);
  Vec2 total =
      has_gravity(spec)
          ? Vec2(rec.factors.back() * body_load_)
          : Vec2(rec.factors.back() * spec.galerkin().body_force * body_area * spec.thickness);
  double magnitude = total.norm();
  for (const auto& b : rec.boundary) total += b.force, magnitude += b.force.norm();
  rec.equilibrium_error = magnitude > 0.0 ? total.norm() / magnitude : 0.0;

  const std::vector<double> all = newton.gather_on_root(d);
  if (spec.galerkin().record_increment_parameters) {
    rec.parameters = all;
    solvers::broadcast(session.comm(), rec.parameters, 0);
  }
  if (root)
    for (int k = 0; k < monitor_table_.rows(); ++k)
      rec.monitor_u.push_back(displacement_at(monitor_table_, k, all));
  if (write_fields) {
    const double time = rec.step + rec.step_fraction;
    const NodalAverage avg = nodal_average(m, st, session);
    gauss_->write(time, st, session);
    if (root) {
      node_u_.resize(R.nodes);
      node_parameters_.resize(R.nodes);
      for (auto& v : node_values_) v.resize(R.nodes);
      for (int I = 0; I < R.nodes; ++I) {
        node_u_[I] = displacement_at(node_table_, I, all);
        node_parameters_[I] = Vec2(all[2 * I], all[2 * I + 1]);
        for (int c = 0; c < 3; ++c) node_values_[c][I] = avg.stress[I](c);
        node_values_[3][I] = avg.stress_zz[I];
        node_values_[4][I] = materials::von_mises(avg.stress[I], avg.stress_zz[I]);
        node_values_[5][I] = avg.plastic_strain[I];
        node_values_[6][I] = avg.plastic[I];
      }
      fields_->write(time);
      display_->write(time, display_fields(display_mesh_, all, avg));
      const int inc = static_cast<int>(R.increments.size());
      for (std::size_t l = 0; l < line_points_.size(); ++l) {
        const ShapeTable& t = line_tables_[l];
        const auto& x = line_points_[l].second;
        for (int k = 0; k < t.rows(); ++k) {
          Vec3 s = Vec3::Zero();
          for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) s += t.phi[q] * avg.stress[t.node[q]];
          const Vec2 uk = displacement_at(t, k, all);
          const double along = (x[k] - line_points_[l].first->from).norm();
          R.lines[l].second.push_back({static_cast<double>(inc), along, x[k].x(), x[k].y(), uk.x(),
                                       uk.y(), s(0), s(1), s(2)});
        }
      }
    }
  }
  R.increments.push_back(std::move(rec));
}

void IncrementRecorder::close() {
  fields_->close();
  gauss_->series->close();
  display_->close();
}

void IncrementRecorder::save(io::Checkpoints& checkpoints, const io::Saver& save) {
  fields_->split(checkpoints.part("fields", checkpoints.generation()));
  gauss_->series->split(checkpoints.part("gauss_points", checkpoints.generation()));
  display_->output().split(checkpoints.part("display_mesh", checkpoints.generation()));
  fields_->for_each_state(save / "fields");
  gauss_->series->for_each_state(save / "gauss_points");
  display_->output().for_each_state(save / "display_mesh");
}

void IncrementRecorder::restore(const io::Loader& load) {
  fields_->for_each_state(load / "fields");
  gauss_->series->for_each_state(load / "gauss_points");
  display_->output().for_each_state(load / "display_mesh");
}

} // namespace mf::implicit
