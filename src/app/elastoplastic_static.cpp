#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/app/elastic_static.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <omp.h>

namespace mf::app {

namespace {

using materials::J2State;
using Clock = std::chrono::steady_clock;

/// The material history and the trial response at this rank's domain points.
struct PointStates {
  std::vector<J2State> committed, trial;
  std::vector<Vec3> stress;
  std::vector<double> stress_zz;
  std::vector<Mat3> tangent;
  std::vector<char> plastic;

  explicit PointStates(std::size_t n)
      : committed(n), trial(n), stress(n, Vec3::Zero()), stress_zz(n, 0.0),
        tangent(n, Mat3::Zero()), plastic(n, 0) {}
};

/// Adds node-block vectors into the owned rows of a plain array.
struct OwnedRowAdder {
  int begin, end;
  double* r;
  void operator()(const int* nodes, int n, const double* v) const {
    for (int a = 0; a < n; ++a) {
      const int I = nodes[a];
      if (I < begin || I >= end) continue;
      r[2 * (I - begin)] += v[2 * a];
      r[2 * (I - begin) + 1] += v[2 * a + 1];
    }
  }
};

/// The discrete equilibrium equations of this rank's rows:
///   R(d) = f_int(d) + K_pen d - sum_c factor_c f_c,
/// with f_c the traction, body-force or penalty right-hand side of condition c at factor 1.
class ElastoplasticSystem {
public:
  ElastoplasticSystem(const io::ProblemSpec& spec, const GalerkinModel& m)
      : spec_(spec), m_(m), params_(*spec.plasticity), states_(m.domain_table.rows()),
        penalty_(m.pattern), tangent_(m.pattern), scatter_(m.domain_table, m.pattern) {
    update_ = spec.model == materials::PlaneModel::PlaneStress ? &materials::j2_update_plane_stress
                                                               : &materials::j2_update_plane_strain;
    const int rows = m.pattern.rows();
    loads_.assign(spec.boundary.size() + 1, std::vector<double>(2 * rows, 0.0));
    counts_in_scale_.assign(loads_.size(), 0);
    const auto add_penalty_matrix = [&](const int* nodes, int n, const double* v) {
      penalty_.add_matrix(nodes, n, v);
    };
    for (std::size_t b = 0; b < m.conditions.size(); ++b) {
      const ConditionPoints& c = m.conditions[b];
      const OwnedRowAdder into{m.pattern.begin, m.pattern.end, loads_[b].data()};
      if (c.bc->constrains) {
        implicit::add_penalty(c.table, c.weight, c.bc->mask, c.bc->penalty, c.values,
                              add_penalty_matrix, into);
      } else {
        implicit::add_load(c.table, c.weight, c.values, into);
        counts_in_scale_[b] = 1;
      }
    }
    if (!spec.body_force.isZero()) {
      const OwnedRowAdder into{m.pattern.begin, m.pattern.end, loads_.back().data()};
      implicit::add_load(m.domain_table, m.domain_weight,
                         std::vector<Vec2>(m.domain_weight.size(), spec.body_force), into);
      counts_in_scale_.back() = 1;
    }
    factors_.assign(loads_.size(), 0.0);
  }

  void set_factors(const std::vector<double>& f) { factors_ = f; }
  const std::vector<double>& factors() const { return factors_; }
  const PointStates& states() const { return states_; }
  double residual_seconds() const { return residual_seconds_; }
  double jacobian_seconds() const { return jacobian_seconds_; }

  /// The history of the converged increment becomes the start of the next one. The trial
  /// response at the converged d stays valid: its stress is what the new history gives there
  /// too, and its tangent, the consistent tangent of the converged increment, is the predictor
  /// for the next one. Recomputed from the new history, every plastic point would sit exactly on
  /// its yield surface and round-off would choose between the elastic and the plastic tangent.
  void commit() { states_.committed = states_.trial; }

  void residual(const std::vector<double>& d, double* r, double& scale_squared) {
    const auto t0 = Clock::now();
    update_materials(d);
    const int rows = m_.pattern.rows();
    std::fill(r, r + 2 * rows, 0.0);
    implicit::add_internal_force(m_.domain_table, m_.domain_weight, states_.stress,
                                 OwnedRowAdder{m_.pattern.begin, m_.pattern.end, r});
    double internal = 0.0, external = 0.0;
    for (int i = 0; i < 2 * rows; ++i) internal += r[i] * r[i];
    penalty_.multiply_add(d, r);
    for (int i = 0; i < 2 * rows; ++i) {
      double applied = 0.0, load = 0.0;
      for (std::size_t c = 0; c < loads_.size(); ++c) {
        applied += factors_[c] * loads_[c][i];
        if (counts_in_scale_[c]) load += factors_[c] * loads_[c][i];
      }
      r[i] -= applied;
      external += load * load;
    }
    scale_squared = internal + external;
    residual_seconds_ += seconds_since(t0);
  }

  void jacobian(const std::vector<double>& d, std::vector<double>& blocks) {
    const auto t0 = Clock::now();
    update_materials(d);
    tangent_.set_values(penalty_.values());
    const implicit::ShapeTable& t = m_.domain_table;
    for (int k = 0; k < t.rows(); ++k) {
      const int n = t.offset[k + 1] - t.offset[k];
      block_.resize(4 * n * n);
      implicit::point_stiffness(t, k, m_.domain_weight[k] * states_.tangent[k], block_.data());
      tangent_.add_matrix_at(scatter_.slots(k), n, block_.data());
    }
    blocks = tangent_.values();
    jacobian_seconds_ += seconds_since(t0);
  }

  /// Every node a point of this rank touches: the entries of d that the residual reads.
  std::vector<int> needed_nodes() const {
    std::vector<int> nodes(m_.domain_table.node);
    nodes.insert(nodes.end(), m_.pattern.column.begin(), m_.pattern.column.end());
    for (const ConditionPoints& c : m_.conditions)
      nodes.insert(nodes.end(), c.table.node.begin(), c.table.node.end());
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }

private:
  /// Return mapping at every point from the committed history and the strain of d. Skipped when
  /// d is the one the trial states already belong to (SNES asks for R and then J at one point).
  void update_materials(const std::vector<double>& d) {
    if (states_valid_ && d == states_d_) return;
    const implicit::ShapeTable& t = m_.domain_table;
    const int n = t.rows();
    int failed = n;
    std::string message;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < n; ++k) {
      const Vec3 eps = implicit::strain_at(t, k, d);
      try {
        MF_REQUIRE(eps.allFinite(), "the strain is not finite");
        const materials::J2Result2D r = update_(params_, eps, states_.committed[k]);
        MF_REQUIRE(r.stress.allFinite(), "the stress is not finite");
        states_.trial[k] = r.state;
        states_.stress[k] = r.stress;
        states_.stress_zz[k] = r.stress_zz;
        states_.tangent[k] = r.tangent;
        states_.plastic[k] = r.plastic;
      } catch (const std::exception& e) {
#pragma omp critical
        if (k < failed) failed = k, message = e.what();
      }
    }
    if (failed < n) {
      states_valid_ = false;
      const Vec2& x = m_.domain.x[m_.domain_mine.rows[failed]];
      fail("material update failed at the Gauss point (", x.x(), ", ", x.y(), "): ", message);
    }
    states_d_ = d;
    states_valid_ = true;
  }

  const io::ProblemSpec& spec_;
  const GalerkinModel& m_;
  materials::J2Parameters params_;
  materials::J2Result2D (*update_)(const materials::J2Parameters&, const Vec3&, const J2State&);
  PointStates states_;
  implicit::BlockRows penalty_;    // K_pen: constant
  implicit::BlockRows tangent_;    // work space for the Jacobian
  implicit::BlockScatter scatter_; // where each point's blocks go in tangent_
  std::vector<double> block_;      // one point's block
  std::vector<std::vector<double>> loads_;
  std::vector<char> counts_in_scale_; // tractions and body force, not penalty right-hand sides
  std::vector<double> factors_;
  std::vector<double> states_d_;
  bool states_valid_ = false;
  double residual_seconds_ = 0.0, jacobian_seconds_ = 0.0;
};

/// Von Mises stress of an in-plane stress with szz.
double von_mises(const Vec3& s, double szz) {
  return materials::von_mises(s, szz);
}

/// The largest of the candidates (value, position) over every rank.
PeakStress peak(double value, const Vec2& at, double sigma_y,
                const solvers::PetscSession& session) {
  struct {
    double value;
    int rank;
  } mine{value, session.rank()}, top{0.0, 0};
  MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, session.comm());
  double x[2] = {at.x(), at.y()};
  MPI_Bcast(x, 2, MPI_DOUBLE, top.rank, session.comm());
  PeakStress p;
  p.von_mises = top.value;
  p.at = Vec2(x[0], x[1]);
  if (top.value > 0.0) p.fraction = sigma_y / top.value;
  return p;
}

/// First yield under the first step's loading (see ElasticLimit).
ElasticLimit elastic_limit(const io::ProblemSpec& spec, const GalerkinModel& m,
                           const solvers::PetscSession& session) {
  ElasticLimit lim;
  const std::vector<double>& target = spec.steps.front().target;
  const implicit::BlockRows rows = assemble_linear_elastic(spec, m, target);
  const implicit::RowPattern& p = rows.pattern();
  solvers::BlockLinearSystem system(session.comm(), m.node_count(), m.own, p.offset, p.column,
                                    rows.values(), rows.rhs(), /*spd=*/true);
  system.solve();
  const std::vector<double> d = system.solution_everywhere();
  const Mat3 C = materials::elastic_matrix(spec.material, spec.model);
  const auto vm_at = [&](const implicit::ShapeTable& t, int k) {
    const Vec3 s = C * implicit::strain_at(t, k, d);
    return von_mises(s, materials::out_of_plane_stress(spec.material, spec.model, s));
  };
  const double sigma_y = spec.plasticity->sigma0;
  double best = -1.0;
  Vec2 where(0.0, 0.0);
  for (int k = 0; k < m.domain_table.rows(); ++k) {
    const double vm = vm_at(m.domain_table, k);
    if (m.domain_mine.counted[k] && vm > best) best = vm, where = m.domain.x[m.domain_mine.rows[k]];
  }
  lim.gauss_points = peak(best, where, sigma_y, session);
  best = -1.0;
  if (session.rank() == 0) {
    const implicit::ShapeTable t = shapes_at(m, m.node_positions(), true);
    for (int k = 0; k < t.rows(); ++k) {
      const double vm = vm_at(t, k);
      if (vm > best) best = vm, where = m.node_positions()[k];
    }
  }
  lim.nodes = peak(best, where, sigma_y, session);
  lim.fraction = lim.nodes.fraction;
  for (double f : target) lim.factors.push_back(lim.fraction * f);
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    BoundaryReport r = boundary_report(m.conditions[b], d, target[b], session);
    r.force *= lim.fraction; // linear elasticity: forces scale with the load
    lim.boundary.push_back(r);
  }
  return lim;
}

/// Sums over this rank's counted points, reduced onto rank 0: a positive weighted average of the
/// Gauss-point values around each node, weights phi_I(x_g)^2 w_g (positive for any shape
/// functions, also where RK or serendipity functions are negative).
struct NodalAverage {
  std::vector<Vec3> stress;
  std::vector<double> stress_zz, plastic_strain, plastic;
};

NodalAverage nodal_average(const GalerkinModel& m, const PointStates& st,
                           const solvers::PetscSession& session) {
  const int N = m.node_count();
  constexpr int kFields = 7; // sxx, syy, sxy, szz, alpha, plastic flag, weight
  std::vector<double> sum(static_cast<std::size_t>(kFields) * N, 0.0);
  const implicit::ShapeTable& t = m.domain_table;
  for (int k = 0; k < t.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    const double v[kFields - 1] = {st.stress[k](0),       st.stress[k](1),
                                   st.stress[k](2),       st.stress_zz[k],
                                   st.committed[k].alpha, static_cast<double>(st.plastic[k])};
    for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) {
      const double a = t.phi[q] * t.phi[q] * w;
      double* s = sum.data() + static_cast<std::size_t>(kFields) * t.node[q];
      for (int f = 0; f < kFields - 1; ++f) s[f] += a * v[f];
      s[kFields - 1] += a;
    }
  }
  if (session.rank() == 0)
    MPI_Reduce(MPI_IN_PLACE, sum.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM, 0,
               session.comm());
  else
    MPI_Reduce(sum.data(), nullptr, static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM, 0,
               session.comm());
  NodalAverage a;
  if (session.rank() != 0) return a;
  a.stress.resize(N);
  a.stress_zz.resize(N);
  a.plastic_strain.resize(N);
  a.plastic.resize(N);
  for (int I = 0; I < N; ++I) {
    const double* s = sum.data() + static_cast<std::size_t>(kFields) * I;
    const double w = s[kFields - 1] > 0.0 ? 1.0 / s[kFields - 1] : 0.0;
    a.stress[I] = Vec3(s[0], s[1], s[2]) * w;
    a.stress_zz[I] = s[3] * w;
    a.plastic_strain[I] = s[4] * w;
    a.plastic[I] = s[5] * w;
  }
  return a;
}

/// Values of this rank's counted points gathered on rank 0, in rank order.
std::vector<double> gather_counted(const std::vector<double>& mine,
                                   const solvers::PetscSession& session) {
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(session.size()), displs(session.size(), 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, session.comm());
  std::vector<double> all;
  if (session.rank() == 0) {
    for (int r = 1; r < session.size(); ++r) displs[r] = displs[r - 1] + counts[r - 1];
    all.resize(displs.back() + counts.back());
  }
  MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
              session.comm());
  return all;
}

/// Gauss-point fields of the counted points, for the gauss_points series.
struct GaussOutput {
  std::vector<int> counted_rows; // table rows of this rank's counted points
  std::unique_ptr<io::FieldSeries> series;

  GaussOutput(const GalerkinModel& m, const solvers::PetscSession& session,
              io::OutputDirectory* out) {
    std::vector<double> x;
    for (int k = 0; k < m.domain_table.rows(); ++k)
      if (m.domain_mine.counted[k]) {
        counted_rows.push_back(k);
        const Vec2& p = m.domain.x[m.domain_mine.rows[k]];
        x.push_back(p.x());
        x.push_back(p.y());
      }
    const std::vector<double> all = gather_counted(x, session);
    if (out) {
      std::vector<Vec2> points(all.size() / 2);
      for (std::size_t i = 0; i < points.size(); ++i) points[i] = Vec2(all[2 * i], all[2 * i + 1]);
      series = std::make_unique<io::FieldSeries>(*out, "gauss_points", points);
    }
  }

  void write(double time, const PointStates& st, const solvers::PetscSession& session) {
    const char* names[] = {"stress_xx", "stress_yy",      "stress_xy", "stress_zz",
                           "von_mises", "plastic_strain", "plastic"};
    io::FieldStep step;
    step.time = time;
    for (int f = 0; f < 7; ++f) {
      std::vector<double> v;
      for (int k : counted_rows) {
        const Vec3& s = st.stress[k];
        const double value[] = {s(0),
                                s(1),
                                s(2),
                                st.stress_zz[k],
                                von_mises(s, st.stress_zz[k]),
                                st.committed[k].alpha,
                                static_cast<double>(st.plastic[k])};
        v.push_back(value[f]);
      }
      std::vector<double> all = gather_counted(v, session);
      if (series) step.scalars.emplace_back(names[f], std::move(all));
    }
    if (series) series->add_step(step);
  }
};

/// True for a condition whose factor changes something: a nonzero prescribed displacement or
/// traction (a clamp's factor does not matter).
bool drives(const io::BoundaryCondition& bc) {
  if (bc.value_from_exact || bc.traction_from_exact) return true;
  return bc.constrains ? !bc.value.cwiseProduct(bc.mask).isZero() : !bc.traction.isZero();
}

/// "pull 0.002, tension 308": the factors of the conditions that drive the body.
std::string factors_text(const io::ProblemSpec& spec, const std::vector<double>& f) {
  std::string s;
  for (std::size_t c = 0; c < spec.boundary.size(); ++c)
    if (drives(spec.boundary[c]))
      s += (s.empty() ? "" : ", ") + spec.boundary[c].name + " " + detail::concat(f[c]);
  if (!spec.body_force.isZero())
    s += (s.empty() ? "" : ", ") + detail::concat("body_force ", f.back());
  return s.empty() ? "no load" : s;
}

} // namespace

ElastoplasticResult solve_elastoplastic_static(const io::ProblemSpec& spec,
                                               const solvers::PetscSession& session,
                                               io::OutputDirectory* out) {
  MF_REQUIRE(spec.plasticity && !spec.steps.empty(),
             "an elastoplastic analysis needs a material with plasticity and steps");
  ElastoplasticResult R;
  const GalerkinModel m = build_galerkin_model(spec, session, R.timer);
  R.method = describe_method(spec.discretisation);
  R.nodes = m.node_count();
  R.dofs = 2 * R.nodes;
  R.domain_points = static_cast<int>(m.domain.x.size());
  R.cells = m.domain.cell_count;
  for (const auto& c : m.conditions) R.boundary_points += static_cast<int>(c.points.x.size());
  double nnz = 4.0 * static_cast<double>(m.pattern.column.size());
  MPI_Allreduce(MPI_IN_PLACE, &nnz, 1, MPI_DOUBLE, MPI_SUM, session.comm());
  R.matrix_nonzeros = nnz;
  log::info("integration: ", R.cells, " background cells, ", R.domain_points, " domain points, ",
            R.boundary_points, " boundary points");

  {
    PhaseTimer::Scope scope(R.timer, "elastic_limit");
    session.collective([&] { R.elastic_limit = elastic_limit(spec, m, session); });
    const ElasticLimit& e = R.elastic_limit;
    const PeakStress& g = e.gauss_points;
    const PeakStress& n = e.nodes;
    log::info("first yield at ", e.fraction, " of step '", spec.steps.front().name, "' (",
              factors_text(spec, e.factors), "); elastic von Mises at its end: ", g.von_mises,
              " at the Gauss point (", g.at.x(), ", ", g.at.y(), "), ", n.von_mises,
              " at the node (", n.at.x(), ", ", n.at.y(), ")");
  }

  ElastoplasticSystem problem(spec, m);
  solvers::NonlinearBlockSystem newton(
      session.comm(), R.nodes, m.own, m.pattern.offset, m.pattern.column, problem.needed_nodes(),
      [&](const std::vector<double>& d, double* r, double& s) { problem.residual(d, r, s); },
      [&](const std::vector<double>& d, std::vector<double>& b) { problem.jacobian(d, b); });
  R.solver = newton.description();
  log::info("Newton: ", R.solver, ", tolerance |R| <= ", spec.nonlinear.tolerance, " |F|");

  // Output helpers, fixed for the run: shape functions at the nodes, monitors and line samples
  // (rank 0), and the field series.
  const bool root = session.rank() == 0;
  implicit::ShapeTable node_table, monitor_table;
  std::vector<std::pair<const io::LineSpec*, std::vector<Vec2>>> line_points;
  std::vector<implicit::ShapeTable> line_tables;
  std::unique_ptr<io::FieldSeries> fields;
  session.collective([&] {
    if (!root) return;
    node_table = shapes_at(m, m.node_positions(), false);
    std::vector<Vec2> mx;
    for (const auto& mon : spec.gauges) mx.push_back(mon.at.head<2>());
    if (!mx.empty()) monitor_table = shapes_at(m, mx, false);
    for (const auto& line : spec.lines) {
      std::vector<Vec2> x;
      for (int k = 0; k < line.points; ++k) {
        const Vec2 p =
            line.from + (line.to - line.from) * (static_cast<double>(k) / (line.points - 1));
        if (spec.domain.contains(p, 1e-9)) x.push_back(p);
      }
      line_tables.push_back(shapes_at(m, x, false));
      line_points.emplace_back(&line, std::move(x));
    }
    if (out)
      fields =
          std::make_unique<io::FieldSeries>(*out, "fields", m.node_positions(), output_cells(m));
  });
  GaussOutput gauss(m, session, root ? out : nullptr);
  for (const auto& [line, x] : line_points)
    R.lines.emplace_back(line->name, std::vector<std::vector<double>>{});

  std::vector<double> d(2 * static_cast<std::size_t>(R.nodes), 0.0);
  const std::size_t nf = spec.boundary.size() + 1;

  // Records the converged state as increment `record.factors`... and writes fields when due.
  const auto record_increment = [&](IncrementRecord rec, bool write_fields) {
    rec.boundary.clear();
    for (std::size_t b = 0; b < m.conditions.size(); ++b)
      rec.boundary.push_back(boundary_report(m.conditions[b], d, rec.factors[b], session));
    double alpha_max = 0.0, body_area = 0.0;
    long plastic = 0;
    const PointStates& st = problem.states();
    for (int k = 0; k < m.domain_table.rows(); ++k) {
      if (!m.domain_mine.counted[k]) continue;
      alpha_max = std::max(alpha_max, st.committed[k].alpha);
      plastic += st.plastic[k];
      body_area += m.domain.weight[m.domain_mine.rows[k]];
    }
    MPI_Allreduce(MPI_IN_PLACE, &alpha_max, 1, MPI_DOUBLE, MPI_MAX, session.comm());
    MPI_Allreduce(MPI_IN_PLACE, &plastic, 1, MPI_LONG, MPI_SUM, session.comm());
    MPI_Allreduce(MPI_IN_PLACE, &body_area, 1, MPI_DOUBLE, MPI_SUM, session.comm());
    rec.max_plastic_strain = alpha_max;
    rec.plastic_points = plastic;
    Vec2 total = rec.factors.back() * spec.body_force * body_area * spec.thickness;
    double magnitude = total.norm();
    for (const auto& b : rec.boundary) total += b.force, magnitude += b.force.norm();
    rec.equilibrium_error = magnitude > 0.0 ? total.norm() / magnitude : 0.0;

    const std::vector<double> all = newton.gather_on_root(d);
    if (root)
      for (int k = 0; k < monitor_table.rows(); ++k)
        rec.monitor_u.push_back(implicit::displacement_at(monitor_table, k, all));
    if (write_fields) {
      const double time = rec.step + rec.step_fraction;
      const NodalAverage avg = nodal_average(m, st, session);
      gauss.write(time, st, session);
      if (root) {
        io::FieldStep step;
        step.time = time;
        std::vector<Vec2> u(R.nodes), params(R.nodes);
        std::vector<double> sxx(R.nodes), syy(R.nodes), sxy(R.nodes), vm(R.nodes);
        for (int I = 0; I < R.nodes; ++I) {
          u[I] = implicit::displacement_at(node_table, I, all);
          params[I] = Vec2(all[2 * I], all[2 * I + 1]);
          sxx[I] = avg.stress[I](0), syy[I] = avg.stress[I](1), sxy[I] = avg.stress[I](2);
          vm[I] = von_mises(avg.stress[I], avg.stress_zz[I]);
        }
        step.vectors = {{"displacement", u}, {"nodal_parameters", params}};
        step.scalars = {{"stress_xx", sxx},
                        {"stress_yy", syy},
                        {"stress_xy", sxy},
                        {"stress_zz", avg.stress_zz},
                        {"von_mises", vm},
                        {"plastic_strain", avg.plastic_strain},
                        {"plastic_fraction", avg.plastic}};
        if (fields) fields->add_step(step);
        const int inc = static_cast<int>(R.increments.size());
        for (std::size_t l = 0; l < line_points.size(); ++l) {
          const implicit::ShapeTable& t = line_tables[l];
          const auto& x = line_points[l].second;
          for (int k = 0; k < t.rows(); ++k) {
            Vec3 s = Vec3::Zero();
            for (int q = t.offset[k]; q < t.offset[k + 1]; ++q)
              s += t.phi[q] * avg.stress[t.node[q]];
            const Vec2 uk = implicit::displacement_at(t, k, all);
            const double along = (x[k] - line_points[l].first->from).norm();
            R.lines[l].second.push_back({static_cast<double>(inc), along, x[k].x(), x[k].y(),
                                         uk.x(), uk.y(), s(0), s(1), s(2)});
          }
        }
      }
    }
    R.increments.push_back(std::move(rec));
  };

  {
    IncrementRecord zero;
    zero.factors.assign(nf, 0.0);
    zero.step = 0;
    zero.step_fraction = 0.0;
    zero.newton.converged = true;
    record_increment(zero, false);
  }

  double newton_seconds = 0.0;
  std::vector<double> current(nf, 0.0);
  solvers::NewtonSettings settings;
  settings.tolerance = spec.nonlinear.tolerance;
  settings.max_iterations = spec.nonlinear.max_iterations;
  int since_output = 0;
  for (std::size_t s = 0; s < spec.steps.size() && R.status == "completed"; ++s) {
    const io::LoadStep& step = spec.steps[s];
    const std::vector<double> start = current;
    const double nominal = 1.0 / step.increments;
    double tau = 0.0, dtau = nominal;
    int cuts = 0, easy = 0;
    while (tau < 1.0 - 1e-12) {
      dtau = std::min(dtau, 1.0 - tau);
      const bool last = tau + dtau >= 1.0 - 1e-12;
      const double to = last ? 1.0 : tau + dtau;
      std::vector<double> f(nf);
      for (std::size_t c = 0; c < nf; ++c) f[c] = start[c] + to * (step.target[c] - start[c]);
      problem.set_factors(f);
      std::vector<double> trial = d;
      const auto t0 = Clock::now();
      solvers::NewtonReport rep = newton.solve(trial, settings);
      newton_seconds += seconds_since(t0);
      if (!rep.converged) {
        const std::string why = rep.reason + (rep.failure.empty() ? "" : ": " + rep.failure);
        if (cuts >= spec.nonlinear.max_cutbacks) {
          R.status = "stopped";
          R.stop_reason = detail::concat(
              "step '", step.name, "': the increment to ", to, " of the step did not converge (",
              why, ") after ", cuts, " cut-backs; the last converged state has factors ",
              factors_text(spec, current),
              ". Under load control this is how a limit load shows: the body cannot carry more; "
              "prescribe a displacement to follow it further.");
          log::warn(R.stop_reason);
          break;
        }
        ++cuts;
        easy = 0;
        dtau *= 0.5;
        log::info("  step '", step.name, "': no convergence towards ", to, " (", why,
                  "); cutting the increment to ", dtau * step.increments, " of nominal");
        continue;
      }
      d = std::move(trial);
      problem.commit();
      tau = to;
      current = f;
      IncrementRecord rec;
      rec.step = static_cast<int>(s);
      rec.step_fraction = tau;
      rec.factors = f;
      rec.newton = rep;
      rec.cutbacks = cuts;
      const bool step_end = last;
      const bool write_fields =
          ++since_output >= spec.fields_every || (step_end && s + 1 == spec.steps.size());
      if (write_fields) since_output = 0;
      {
        PhaseTimer::Scope scope(R.timer, "increment_output");
        record_increment(std::move(rec), write_fields);
      }
      const IncrementRecord& done = R.increments.back();
      log::info("  step '", step.name, "' at ", tau, " (", factors_text(spec, f),
                "): ", rep.iterations, " Newton iterations, |R|/|F| ",
                rep.residual.back() / std::max(rep.scale.back(), 1e-300), ", plastic points ",
                done.plastic_points, ", max plastic strain ", done.max_plastic_strain);
      // A cut increment grows back, doubling after every two easy ones, up to the nominal size.
      if (dtau < nominal && rep.iterations <= 6 && ++easy >= 2) {
        dtau = std::min(nominal, 2.0 * dtau);
        easy = 0;
      }
      cuts = 0;
    }
  }
  R.timer.add("newton", newton_seconds);
  R.residual_seconds = problem.residual_seconds();
  R.jacobian_seconds = problem.jacobian_seconds();
  if (fields) fields->close();
  if (gauss.series) gauss.series->close();
  return R;
}

void write_elastoplastic_outputs(const io::ProblemSpec& spec, const ElastoplasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  // history.csv: one row per converged increment, increment 0 the unloaded state.
  std::vector<std::string> header{"increment", "step", "step_fraction"};
  for (const auto& bc : spec.boundary) header.push_back("factor_" + bc.name);
  for (const auto& bc : spec.boundary) {
    const std::string kind = bc.constrains ? "reaction_" : "load_";
    header.push_back(kind + bc.name + "_x");
    header.push_back(kind + bc.name + "_y");
  }
  for (const auto& mon : spec.gauges) {
    header.push_back("ux_" + mon.name);
    header.push_back("uy_" + mon.name);
  }
  header.insert(header.end(), {"max_plastic_strain", "plastic_points", "newton_iterations",
                               "cutbacks", "residual_relative", "equilibrium_error"});
  std::vector<std::vector<double>> rows;
  long newton_total = 0;
  int cut_total = 0;
  for (std::size_t i = 0; i < r.increments.size(); ++i) {
    const IncrementRecord& inc = r.increments[i];
    std::vector<double> row{static_cast<double>(i), static_cast<double>(inc.step),
                            inc.step_fraction};
    for (std::size_t c = 0; c < spec.boundary.size(); ++c) row.push_back(inc.factors[c]);
    for (const auto& b : inc.boundary) row.insert(row.end(), {b.force.x(), b.force.y()});
    for (const auto& u : inc.monitor_u) row.insert(row.end(), {u.x(), u.y()});
    const double rel = inc.newton.residual.empty()
                           ? 0.0
                           : inc.newton.residual.back() / std::max(inc.newton.scale.back(), 1e-300);
    row.insert(row.end(), {inc.max_plastic_strain, static_cast<double>(inc.plastic_points),
                           static_cast<double>(inc.newton.iterations),
                           static_cast<double>(inc.cutbacks), rel, inc.equilibrium_error});
    rows.push_back(row);
    newton_total += inc.newton.iterations;
    cut_total += inc.cutbacks;
  }
  out.write_csv("history.csv", header, rows);
  for (const auto& [name, line_rows] : r.lines)
    out.write_csv("line_" + name + ".csv",
                  {"increment", "s", "x", "y", "ux", "uy", "stress_xx", "stress_yy", "stress_xy"},
                  line_rows);

  io::Json counts, times, results, solver, limit, last, steps;
  const int increments = static_cast<int>(r.increments.size()) - 1;
  counts.set("nodes", r.nodes)
      .set("dofs", r.dofs)
      .set("background_cells", r.cells)
      .set("domain_points", r.domain_points)
      .set("boundary_points", r.boundary_points)
      .set("matrix_nonzeros", r.matrix_nonzeros)
      .set("increments", increments)
      .set("newton_iterations", newton_total)
      .set("cutbacks", cut_total);
  double newton_s = 0.0;
  for (const auto& [name, sec] : r.timer.phases()) {
    times.set(name, sec);
    if (name == "newton") newton_s = sec;
  }
  io::Json newton_parts;
  newton_parts.set("residual_and_return_mapping", r.residual_seconds)
      .set("jacobian_assembly", r.jacobian_seconds)
      .set("linear_solves_and_other", newton_s - r.residual_seconds - r.jacobian_seconds);
  times.set("newton_parts", newton_parts);
  times.set("total", r.timer.total());
  solver.set("type", r.solver).set("tolerance", spec.nonlinear.tolerance);

  const ElasticLimit& e = r.elastic_limit;
  io::Json lim_factors, lim_forces;
  for (std::size_t c = 0; c < spec.boundary.size(); ++c) {
    lim_factors.set(spec.boundary[c].name, e.factors[c]);
    lim_forces.set(spec.boundary[c].name,
                   std::vector<double>{e.boundary[c].force.x(), e.boundary[c].force.y()});
  }
  const auto peak_json = [](const PeakStress& p) {
    io::Json j;
    j.set("max_von_mises_at_first_step_end", p.von_mises)
        .set("at", std::vector<double>{p.at.x(), p.at.y()})
        .set("fraction_of_first_step", p.fraction);
    return j;
  };
  limit.set("fraction_of_first_step", e.fraction)
      .set("factors", lim_factors)
      .set("forces", lim_forces)
      .set("gauss_points", peak_json(e.gauss_points))
      .set("nodes", peak_json(e.nodes));

  const IncrementRecord& fin = r.increments.back();
  io::Json fin_factors, fin_forces, fin_monitors;
  for (std::size_t c = 0; c < spec.boundary.size(); ++c) {
    fin_factors.set(spec.boundary[c].name, fin.factors[c]);
    fin_forces.set(spec.boundary[c].name,
                   std::vector<double>{fin.boundary[c].force.x(), fin.boundary[c].force.y()});
  }
  for (std::size_t k = 0; k < spec.gauges.size() && k < fin.monitor_u.size(); ++k)
    fin_monitors.set(spec.gauges[k].name,
                     std::vector<double>{fin.monitor_u[k].x(), fin.monitor_u[k].y()});
  last.set("factors", fin_factors)
      .set("forces", fin_forces)
      .set("monitors", fin_monitors)
      .set("max_plastic_strain", fin.max_plastic_strain)
      .set("plastic_points", fin.plastic_points)
      .set("equilibrium_error", fin.equilibrium_error);
  for (std::size_t s = 0; s < spec.steps.size(); ++s) {
    std::vector<double> its;
    for (const auto& inc : r.increments)
      if (&inc != &r.increments.front() && inc.step == static_cast<int>(s))
        its.push_back(inc.newton.iterations);
    io::Json js;
    js.set("increments_planned", spec.steps[s].increments)
        .set("increments_done", static_cast<int>(its.size()))
        .set("newton_iterations", its);
    steps.set(spec.steps[s].name, js);
  }
  results.set("elastic_limit", limit).set("final", last).set("steps", steps);
  io::Json summary;
  summary.set("problem", spec.name)
      .set("description", spec.description)
      .set("units", spec.units)
      .set("analysis", "elastoplastic_static")
      .set("method", r.method)
      .set("status", r.status);
  if (!r.stop_reason.empty()) summary.set("stop_reason", r.stop_reason);
  summary.set("mpi_ranks", session.size())
      .set("openmp_threads", omp_get_max_threads())
      .set("counts", counts)
      .set("solver", solver)
      .set("time_s", times)
      .set("results", results);
  out.write_text("summary.json", summary.str() + "\n");
}

} // namespace mf::app
