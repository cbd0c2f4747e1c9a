#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::implicit {

namespace {

const char* kAxes[3] = {"x", "y", "z"};

void write_history(const spec::ProblemSpec& spec, const SolidElastoplasticResult& r,
                   io::OutputDirectory& out) {
  io::History history({"increment", "step"});
  const spec::SolidSpec& s = spec.solid();
  for (const spec::FaceCondition& bc : s.boundary) history.add_column("factor_" + bc.name);
  history.add_column("factor_body_force");
  for (const FaceReport& f : r.increments.front().faces) {
    for (const char* a : kAxes)
      history.add_column((f.constraint ? "reaction_" : "load_") + f.name + "_" + a);
    history.add_column("normal_displacement_" + f.name);
  }
  for (const spec::GaugeSpec& g : s.gauges)
    for (const char* a : kAxes) history.add_column("u" + std::string(a) + "_" + g.name);
  for (const char* c : {"newton_iterations", "linear_iterations", "cutbacks", "plastic_points",
                        "max_plastic_strain"})
    history.add_column(c);
  for (std::size_t k = 0; k < r.increments.size(); ++k) {
    const SolidIncrement& inc = r.increments[k];
    std::vector<double> row{static_cast<double>(k), static_cast<double>(inc.record.step)};
    row.insert(row.end(), inc.record.factors.begin(), inc.record.factors.end());
    for (const FaceReport& f : inc.faces)
      row.insert(row.end(), {f.force.x(), f.force.y(), f.force.z(), f.normal_displacement});
    for (const Vec3& u : inc.gauges) row.insert(row.end(), {u.x(), u.y(), u.z()});
    row.insert(row.end(),
               {static_cast<double>(inc.record.newton.iterations),
                static_cast<double>(inc.record.newton.linear_iterations),
                static_cast<double>(inc.record.cutbacks),
                static_cast<double>(inc.record.plastic_points), inc.record.max_plastic_strain});
    history.append(std::move(row));
  }
  history.write(out);
}

void write_summary(const spec::ProblemSpec& spec, const SolidElastoplasticResult& r,
                   const solvers::PetscSession& session, io::OutputDirectory& out) {
  io::Summary summary({spec.name, spec.description, spec.units, "elastoplastic_static",
                       describe_solid_method(spec)});
  summary.set_status(r.status, r.stop_reason);
  summary.set("mpi_ranks", session.size()).set("openmp_threads", omp_get_max_threads());
  long newton = 0, linear = 0, tangents = 0;
  for (const SolidIncrement& inc : r.increments) {
    newton += inc.record.newton.iterations;
    linear += inc.record.newton.linear_iterations;
    tangents += inc.record.newton.tangents;
  }
  summary.section("counts")
      .set("nodes", r.counts.nodes)
      .set("dofs", r.counts.dofs)
      .set("domain_points", r.counts.domain_points)
      .set("boundary_points", r.counts.boundary_points)
      .set("increments", static_cast<long>(r.increments.size()) - 1)
      .set("newton_iterations", newton)
      .set("linear_iterations", linear);
  summary.section("memory")
      .set("peak_bytes_largest_rank", r.memory.largest_rank)
      .set("peak_bytes_all_ranks", r.memory.all_ranks)
      .set("peak_bytes_per_dof", r.memory.all_ranks / std::max(1, r.counts.dofs));
  summary.section("solver")
      .set("type", r.solver)
      .set("keep_tangent", spec.solid().nonlinear.keep_tangent)
      .set("tangents", tangents);
  const SolidIncrement& last = r.increments.back();
  io::Json boundary;
  for (const FaceReport& f : last.faces) {
    io::Json j;
    j.set("kind", f.constraint ? "displacement" : "traction");
    j.set(f.constraint ? "reaction" : "applied_force",
          std::vector<double>{f.force.x(), f.force.y(), f.force.z()});
    boundary.set(f.name, j);
  }
  double umax = 0.0;
  for (const Vec3& u : r.node_u) umax = std::max(umax, u.norm());
  summary.section("results")
      .set("max_displacement", umax)
      .set("max_plastic_strain", last.record.max_plastic_strain)
      .set("plastic_points", last.record.plastic_points)
      .set("boundary", boundary);
  summary.write(out, r.timer);
}

} // namespace

void write_solid_elastoplastic_outputs(const spec::ProblemSpec& spec,
                                       const SolidElastoplasticResult& r,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  write_history(spec, r, out);
  if (r.lines) r.lines->write(out);
  write_summary(spec, r, session, out);
}

} // namespace mf::implicit
