#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/verification/exact_solutions_3d.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::implicit {

namespace {

const char* kAxes[3] = {"x", "y", "z"};

void write_fields(const spec::ProblemSpec& spec, const SolidElasticResult& r,
                  io::OutputDirectory& out) {
  std::vector<double> xyz;
  for (const Vec3& x : r.node_x) xyz.insert(xyz.end(), {x.x(), x.y(), x.z()});
  io::FieldOutput fields(&out, "fields", xyz);
  fields.vector("displacement", [&](std::vector<double>& v) {
    v.clear();
    for (const Vec3& u : r.node_u) v.insert(v.end(), {u.x(), u.y(), u.z()});
  });
  fields.vector("nodal_parameters", [&](std::vector<double>& v) { v = r.parameters; });
  add_node_stress_fields(fields, r.node_stress, 6);
  if (spec.solid().exact)
    fields.vector("displacement_exact", [&](std::vector<double>& v) {
      v.clear();
      for (const Vec3& x : r.node_x) {
        const Vec3 u =
            verification::exact_displacement_3d(*spec.solid().exact, spec.elasticity(), x);
        v.insert(v.end(), {u.x(), u.y(), u.z()});
      }
    });
  fields.write(1.0);
  fields.close();
}

void write_history(const spec::ProblemSpec& spec, const SolidElasticResult& r, double umax,
                   io::OutputDirectory& out) {
  io::History history({"step", "load_factor"});
  std::vector<double> row{1.0, 1.0};
  for (const FaceReport& b : r.boundary)
    for (int c = 0; c < 3; ++c) {
      history.add_column((b.constraint ? "reaction_" : "load_") + b.name + "_" + kAxes[c]);
      row.push_back(b.force(c));
    }
  for (std::size_t k = 0; k < r.gauge_u.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      history.add_column("u" + std::string(kAxes[c]) + "_" + spec.solid().gauges[k].name);
      row.push_back(r.gauge_u[k](c));
    }
  for (const char* c : {"max_displacement", "solver_iterations"}) history.add_column(c);
  row.insert(row.end(), {umax, static_cast<double>(r.solve.iterations)});
  history.append(std::move(row));
  history.write(out);
}

void write_summary(const spec::ProblemSpec& spec, const SolidElasticResult& r,
                   const solvers::PetscSession& session, double umax, io::OutputDirectory& out) {
  io::Summary summary(
      {spec.name, spec.description, spec.units, "elastic_static", describe_solid_method(spec)});
  summary.set("mpi_ranks", session.size()).set("openmp_threads", omp_get_max_threads());
  summary.section("counts")
      .set("nodes", r.counts.nodes)
      .set("dofs", r.counts.dofs)
      .set("domain_points", r.counts.domain_points)
      .set("boundary_points", r.counts.boundary_points)
      .set("mean_nodes_per_point", r.counts.mean_support)
      .set("matrix_nonzeros", r.matrix_nonzeros);
  summary.section("memory")
      .set("peak_bytes_largest_rank", r.memory.largest_rank)
      .set("peak_bytes_all_ranks", r.memory.all_ranks)
      .set("peak_bytes_per_dof", r.memory.all_ranks / std::max(1, r.counts.dofs));
  summary.section("solver")
      .set("type", r.solve.solver)
      .set("iterations", r.solve.iterations)
      .set("reason", r.solve.reason_name)
      .set("relative_residual", r.solve.residual_norm);
  io::Json boundary;
  double violation = 0.0;
  for (const FaceReport& b : r.boundary) {
    io::Json j;
    j.set("kind", b.constraint ? "displacement" : "traction");
    j.set(b.constraint ? "reaction" : "applied_force",
          std::vector<double>{b.force.x(), b.force.y(), b.force.z()});
    if (b.constraint) j.set("violation_max", b.violation_max);
    violation = std::max(violation, b.violation_max);
    boundary.set(b.name, j);
  }
  io::Json& results = summary.section("results");
  results.set("max_displacement", umax)
      .set("constraint_violation_max", violation)
      .set("boundary", boundary);
  if (spec.solid().exact)
    results.set("error_l2_relative", r.error_l2).set("error_energy_relative", r.error_energy);
  summary.write(out, r.timer);
}

} // namespace

void write_solid_elastic_outputs(const spec::ProblemSpec& spec, const SolidElasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  write_fields(spec, r, out);
  double umax = 0.0;
  for (const Vec3& u : r.node_u) umax = std::max(umax, u.norm());
  write_history(spec, r, umax, out);
  if (r.lines) r.lines->write(out);
  write_summary(spec, r, session, umax, out);
}

} // namespace mf::implicit
