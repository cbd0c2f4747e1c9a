#include "meshfree/implicit/elastic_output.hpp"
#include "meshfree/implicit/adaptivity_output.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/verification/exact_solutions.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::implicit {

namespace {

/// Stress components and von Mises stress at the nodes, one vector each for the field output.
struct NodeStresses {
  std::vector<double> sxx, syy, sxy, vm;
};

NodeStresses node_stresses(const ElasticResult& r) {
  NodeStresses s;
  for (std::size_t i = 0; i < r.node_x.size(); ++i) {
    s.sxx.push_back(r.node_stress[i](0));
    s.syy.push_back(r.node_stress[i](1));
    s.sxy.push_back(r.node_stress[i](2));
    s.vm.push_back(materials::von_mises(r.node_stress[i], r.node_szz[i]));
  }
  return s;
}

/// fields/: the nodal displacements, parameters, exact displacements and stresses, and the
/// display mesh's series.
void write_fields(const spec::ProblemSpec& spec, const ElasticResult& r,
                  const materials::IsotropicElastic& exact_mat, const NodeStresses& st,
                  io::OutputDirectory& out) {
  io::FieldOutput fields(&out, "fields", r.node_x, r.output_cells);
  fields.vector2("displacement", [&](std::vector<Vec2>& v) { v = r.node_u; });
  fields.vector2("nodal_parameters", [&](std::vector<Vec2>& v) {
    v.resize(r.node_x.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      v[i] = Vec2(r.parameters[2 * i], r.parameters[2 * i + 1]);
  });
  if (spec.galerkin().exact)
    fields.vector2("displacement_exact", [&](std::vector<Vec2>& v) {
      v.clear();
      for (const auto& x : r.node_x)
        v.push_back(verification::exact_displacement(*spec.galerkin().exact, exact_mat, x));
    });
  fields.scalar("stress_xx", st.sxx);
  fields.scalar("stress_yy", st.syy);
  fields.scalar("stress_xy", st.sxy);
  fields.scalar("stress_zz", r.node_szz);
  fields.scalar("von_mises", st.vm);
  fields.write(1.0);
  fields.close();
  DisplaySeries display(&out, r.display_mesh);
  display.write(1.0, r.display);
  display.close();
}

/// line_<name>.csv: the sampled lines, with the exact solution beside them when there is one.
void write_lines(const spec::ProblemSpec& spec, const ElasticResult& r,
                 const materials::IsotropicElastic& exact_mat, io::OutputDirectory& out) {
  for (const auto& [name, s] : r.lines) {
    std::vector<std::string> header{"s",  "x",         "y",         "ux",
                                    "uy", "stress_xx", "stress_yy", "stress_xy"};
    if (spec.galerkin().exact)
      header.insert(header.end(), {"ux_exact", "uy_exact", "stress_xx_exact", "stress_yy_exact",
                                   "stress_xy_exact"});
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      std::vector<double> row{s.s[k],     s.x[k].x(),     s.x[k].y(),     s.u[k].x(),
                              s.u[k].y(), s.stress[k](0), s.stress[k](1), s.stress[k](2)};
      if (spec.galerkin().exact) {
        const Vec2 ue = verification::exact_displacement(*spec.galerkin().exact, exact_mat, s.x[k]);
        const Vec3 se = verification::exact_stress(*spec.galerkin().exact, exact_mat, s.x[k]);
        row.insert(row.end(), {ue.x(), ue.y(), se(0), se(1), se(2)});
      }
      rows.push_back(row);
    }
    out.write_csv("line_" + name + ".csv", header, rows);
  }
}

/// history.csv: the single step's boundary forces, gauges and maxima.
void write_history(const spec::ProblemSpec& spec, const ElasticResult& r, double umax, double vmmax,
                   io::OutputDirectory& out) {
  io::History history({"step", "load_factor"});
  std::vector<double> row{1.0, 1.0};
  for (const auto& b : r.boundary) {
    const std::string kind = b.constraint ? "reaction_" : "load_";
    history.add_column(kind + b.name + "_x");
    history.add_column(kind + b.name + "_y");
    row.push_back(b.force.x());
    row.push_back(b.force.y());
  }
  const std::vector<spec::GaugeSpec>& gauges = spec.galerkin().gauges;
  for (std::size_t k = 0; k < gauges.size(); ++k) {
    history.add_column("ux_" + gauges[k].name);
    history.add_column("uy_" + gauges[k].name);
    row.insert(row.end(), {r.gauge_u[k].x(), r.gauge_u[k].y()});
  }
  for (const char* c : {"max_displacement", "max_von_mises", "solver_iterations"})
    history.add_column(c);
  row.insert(row.end(), {umax, vmmax, static_cast<double>(r.solve.iterations)});
  history.append(std::move(row));
  history.write(out);
}

/// The counts, memory and solver sections of summary.json.
void describe_run(const ElasticResult& r, io::Summary& summary) {
  summary.section("counts")
      .set("nodes", r.nodes)
      .set("dofs", r.dofs)
      .set("background_cells", r.cells)
      .set("domain_points", r.domain_points)
      .set("boundary_points", r.boundary_points)
      .set("mean_nodes_per_point", r.mean_support)
      .set("matrix_nonzeros", r.matrix_nonzeros)
      .set("steps", 1)
      .set("newton_iterations", 0);
  summary.section("memory")
      .set("peak_bytes_largest_rank", r.memory.largest_rank)
      .set("peak_bytes_all_ranks", r.memory.all_ranks);
  summary.section("solver")
      .set("type", r.solve.solver)
      .set("iterations", r.solve.iterations)
      .set("reason", r.solve.reason_name)
      .set("relative_residual", r.solve.residual_norm);
}

/// results.boundary: each condition's reaction or applied force.
io::Json boundary_json(const ElasticResult& r) {
  io::Json bnd;
  for (const auto& b : r.boundary) {
    io::Json j;
    j.set("kind", b.constraint ? "displacement" : "traction");
    j.set(b.constraint ? "reaction" : "applied_force",
          std::vector<double>{b.force.x(), b.force.y()});
    if (b.constraint) j.set("violation_max", b.violation_max);
    bnd.set(b.name, j);
  }
  return bnd;
}

void write_summary(const spec::ProblemSpec& spec, const ElasticResult& r,
                   const solvers::PetscSession& session, double umax, double vmmax,
                   io::OutputDirectory& out) {
  io::Summary summary({spec.name, spec.description, spec.units, "elastic_static",
                       describe_method(spec.galerkin().discretisation, spec.domain)});
  summary.set("mpi_ranks", session.size()).set("openmp_threads", omp_get_max_threads());
  describe_run(r, summary);
  io::Json& results = summary.section("results");
  results.set("max_displacement", umax)
      .set("max_von_mises", vmmax)
      .set("constraint_violation_max", r.violation_max)
      .set("constraint_violation_relative", r.violation_relative)
      .set("boundary", boundary_json(r));
  if (spec.galerkin().exact)
    results.set("error_l2_relative", r.error_l2).set("error_energy_relative", r.error_energy);
  if (r.adaptation) results.set("adaptivity", adaptation_json(spec, *r.adaptation, r.estimate));
  summary.write(out, r.timer);
}

} // namespace

void write_elastic_outputs(const spec::ProblemSpec& spec, const ElasticResult& r,
                           const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  const materials::IsotropicElastic exact_mat =
      materials::plane_stress_equivalent(spec.elasticity(), spec.model);
  const NodeStresses stresses = node_stresses(r);
  write_fields(spec, r, exact_mat, stresses, out);
  write_lines(spec, r, exact_mat, out);
  double umax = 0.0, vmmax = 0.0;
  for (const auto& u : r.node_u) umax = std::max(umax, u.norm());
  for (double v : stresses.vm) vmmax = std::max(vmmax, v);
  write_history(spec, r, umax, vmmax, out);
  if (r.adaptation) write_adaptation(spec, *r.adaptation, r.estimate, 0, out);
  write_summary(spec, r, session, umax, vmmax, out);
}

} // namespace mf::implicit
