#include "meshfree/implicit/elastic_output.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/verification/exact_solutions.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::implicit {

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

} // namespace mf::implicit
