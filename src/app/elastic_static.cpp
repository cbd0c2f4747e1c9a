#include "meshfree/app/elastic_static.hpp"
#include "meshfree/app/galerkin_model.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::app {

namespace {

using implicit::Csr;
using implicit::ShapeTable;

/// Fields at arbitrary points (nodes, line samples): u^h, stress, szz.
void evaluate_fields(const GalerkinModel& m, const io::ProblemSpec& spec,
                     const std::vector<Vec2>& x, const std::vector<double>& d, std::vector<Vec2>& u,
                     std::vector<Vec3>& stress, std::vector<double>& szz) {
  const ShapeTable t = shapes_at(m, x, true);
  const Mat3 C = materials::elastic_matrix(spec.material, spec.model);
  u.resize(x.size());
  stress.resize(x.size());
  szz.resize(x.size());
  for (int r = 0; r < t.rows(); ++r) {
    u[r] = implicit::displacement_at(t, r, d);
    stress[r] = C * implicit::strain_at(t, r, d);
    szz[r] = materials::out_of_plane_stress(spec.material, spec.model, stress[r]);
  }
}

} // namespace

std::string describe_method(const io::DiscretisationSpec& d) {
  if (d.method == io::Method::Fem) {
    std::string e = d.fem.element;
    for (char& c : e) c = static_cast<char>(std::toupper(c));
    return "FE " + e + (d.fem.mesh.empty() ? " on a structured mesh" : " on " + d.fem.mesh);
  }
  const auto& s = d.shape;
  std::string m = s.approximation == kernels::Approximation::ReproducingKernel    ? "RK"
                  : s.approximation == kernels::Approximation::MovingLeastSquares ? "MLS/EFG"
                                                                                  : "SPH";
  m += s.basis == kernels::Basis::Linear ? " Galerkin, linear basis, "
                                         : " Galerkin, quadratic basis, ";
  m += s.window.type == kernels::WindowType::CubicSpline     ? "cubic B-spline"
       : s.window.type == kernels::WindowType::QuarticSpline ? "quartic spline"
                                                             : "truncated Gaussian";
  m += s.support == kernels::SupportShape::Circular ? " window, circular supports"
                                                    : " window, rectangular supports";
  return m;
}

namespace {

/// Relative L2 and energy-norm errors against the exact solution, over the whole body.
std::pair<double, double> exact_errors(const io::ProblemSpec& spec, const GalerkinModel& m,
                                       const std::vector<double>& d,
                                       const solvers::PetscSession& session) {
  const Mat3 C = materials::elastic_matrix(spec.material, spec.model);
  const Mat3 Cinv = C.inverse();
  const materials::IsotropicElastic exact_mat =
      materials::plane_stress_equivalent(spec.material, spec.model);
  double sums[4] = {0, 0, 0, 0}; // |e_u|^2, |u|^2, e_eps.C.e_eps, eps.C.eps
  for (int k = 0; k < m.domain_table.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    const Vec2& x = m.domain.x[m.domain_mine.rows[k]];
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    const Vec2 ue = verification::exact_displacement(*spec.exact, exact_mat, x);
    const Vec3 ee = Cinv * verification::exact_stress(*spec.exact, exact_mat, x);
    const Vec2 eu = implicit::displacement_at(m.domain_table, k, d) - ue;
    const Vec3 eps = implicit::strain_at(m.domain_table, k, d) - ee;
    sums[0] += w * eu.squaredNorm();
    sums[1] += w * ue.squaredNorm();
    sums[2] += w * eps.dot(C * eps);
    sums[3] += w * ee.dot(C * ee);
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, session.comm());
  return {std::sqrt(sums[0] / sums[1]), std::sqrt(sums[2] / sums[3])};
}

/// u^h and stresses at the nodes and along the sample lines (on the calling rank).
void sample_fields(const io::ProblemSpec& spec, const GalerkinModel& m, ElasticResult& R) {
  const auto& d = R.parameters;
  R.node_x = m.node_positions();
  evaluate_fields(m, spec, R.node_x, d, R.node_u, R.node_stress, R.node_szz);
  for (const auto& line : spec.lines) {
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

ElasticResult solve_elastic_static(const io::ProblemSpec& spec,
                                   const solvers::PetscSession& session) {
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
    const implicit::BlockRows rows =
        assemble_linear_elastic(spec, m, std::vector<double>(spec.boundary.size() + 1, 1.0));
    const implicit::RowPattern& p = rows.pattern();
    system = std::make_unique<solvers::BlockLinearSystem>(session.comm(), R.nodes, m.own, p.offset,
                                                          p.column, rows.values(), rows.rhs(),
                                                          /*spd=*/true);
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
  if (spec.exact)
    std::tie(R.error_l2, R.error_energy) = exact_errors(spec, m, R.parameters, session);
  for (const auto& c : m.conditions) {
    R.boundary.push_back(boundary_report(c, R.parameters, 1.0, session));
    R.violation_max = std::max(R.violation_max, R.boundary.back().violation_max);
  }
  session.collective([&] {
    if (session.rank() != 0) return;
    sample_fields(spec, m, R);
    R.output_cells = output_cells(m);
    double umax = 0.0;
    for (const auto& u : R.node_u) umax = std::max(umax, u.norm());
    R.violation_relative = umax > 0.0 ? R.violation_max / umax : 0.0;
  });
  return R;
}

void write_elastic_outputs(const io::ProblemSpec& spec, const ElasticResult& r,
                           const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  const materials::IsotropicElastic exact_mat =
      materials::plane_stress_equivalent(spec.material, spec.model);
  io::FieldStep step;
  step.time = 1.0;
  std::vector<double> sxx, syy, sxy, vm, vol, rad;
  for (std::size_t i = 0; i < r.node_x.size(); ++i) {
    sxx.push_back(r.node_stress[i](0));
    syy.push_back(r.node_stress[i](1));
    sxy.push_back(r.node_stress[i](2));
    vm.push_back(materials::von_mises(r.node_stress[i], r.node_szz[i]));
  }
  std::vector<Vec2> params(r.node_x.size());
  for (std::size_t i = 0; i < params.size(); ++i)
    params[i] = Vec2(r.parameters[2 * i], r.parameters[2 * i + 1]);
  step.vectors = {{"displacement", r.node_u}, {"nodal_parameters", params}};
  step.scalars = {{"stress_xx", sxx},
                  {"stress_yy", syy},
                  {"stress_xy", sxy},
                  {"stress_zz", r.node_szz},
                  {"von_mises", vm}};
  if (spec.exact) {
    std::vector<Vec2> ue;
    for (const auto& x : r.node_x)
      ue.push_back(verification::exact_displacement(*spec.exact, exact_mat, x));
    step.vectors.emplace_back("displacement_exact", ue);
  }
  out.write_fields(r.node_x, {step}, r.output_cells);

  for (const auto& [name, s] : r.lines) {
    std::vector<std::string> header{"s",  "x",         "y",         "ux",
                                    "uy", "stress_xx", "stress_yy", "stress_xy"};
    if (spec.exact)
      header.insert(header.end(), {"ux_exact", "uy_exact", "stress_xx_exact", "stress_yy_exact",
                                   "stress_xy_exact"});
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      std::vector<double> row{s.s[k],     s.x[k].x(),     s.x[k].y(),     s.u[k].x(),
                              s.u[k].y(), s.stress[k](0), s.stress[k](1), s.stress[k](2)};
      if (spec.exact) {
        const Vec2 ue = verification::exact_displacement(*spec.exact, exact_mat, s.x[k]);
        const Vec3 se = verification::exact_stress(*spec.exact, exact_mat, s.x[k]);
        row.insert(row.end(), {ue.x(), ue.y(), se(0), se(1), se(2)});
      }
      rows.push_back(row);
    }
    out.write_csv("line_" + name + ".csv", header, rows);
  }

  double umax = 0.0, vmmax = 0.0;
  for (const auto& u : r.node_u) umax = std::max(umax, u.norm());
  for (double v : vm) vmmax = std::max(vmmax, v);
  std::vector<std::string> header{"step", "load_factor"};
  std::vector<double> row{1.0, 1.0};
  for (const auto& b : r.boundary) {
    const std::string kind = b.constraint ? "reaction_" : "load_";
    header.push_back(kind + b.name + "_x");
    header.push_back(kind + b.name + "_y");
    row.push_back(b.force.x());
    row.push_back(b.force.y());
  }
  header.insert(header.end(), {"max_displacement", "max_von_mises", "solver_iterations"});
  row.insert(row.end(), {umax, vmmax, static_cast<double>(r.solve.iterations)});
  out.write_csv("history.csv", header, {row});

  io::Json counts, times, results, bnd, solver;
  counts.set("nodes", r.nodes)
      .set("dofs", r.dofs)
      .set("background_cells", r.cells)
      .set("domain_points", r.domain_points)
      .set("boundary_points", r.boundary_points)
      .set("mean_nodes_per_point", r.mean_support)
      .set("matrix_nonzeros", r.matrix_nonzeros)
      .set("steps", 1)
      .set("newton_iterations", 0);
  for (const auto& [name, sec] : r.timer.phases()) times.set(name, sec);
  times.set("total", r.timer.total());
  solver.set("type", r.solve.solver)
      .set("iterations", r.solve.iterations)
      .set("reason", r.solve.reason_name)
      .set("relative_residual", r.solve.residual_norm);
  for (const auto& b : r.boundary) {
    io::Json j;
    j.set("kind", b.constraint ? "displacement" : "traction");
    j.set(b.constraint ? "reaction" : "applied_force",
          std::vector<double>{b.force.x(), b.force.y()});
    if (b.constraint) j.set("violation_max", b.violation_max);
    bnd.set(b.name, j);
  }
  results.set("max_displacement", umax)
      .set("max_von_mises", vmmax)
      .set("constraint_violation_max", r.violation_max)
      .set("constraint_violation_relative", r.violation_relative)
      .set("boundary", bnd);
  if (spec.exact)
    results.set("error_l2_relative", r.error_l2).set("error_energy_relative", r.error_energy);
  io::Json summary;
  summary.set("problem", spec.name)
      .set("description", spec.description)
      .set("units", spec.units)
      .set("analysis", "elastic_static")
      .set("method", describe_method(spec.discretisation))
      .set("status", "completed")
      .set("mpi_ranks", session.size())
      .set("openmp_threads", omp_get_max_threads())
      .set("counts", counts)
      .set("solver", solver)
      .set("time_s", times)
      .set("results", results);
  out.write_text("summary.json", summary.str() + "\n");
}

} // namespace mf::app
