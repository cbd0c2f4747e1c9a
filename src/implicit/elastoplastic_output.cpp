#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/adaptivity_output.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/results.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::implicit {

namespace {

/// Newton and linear iterations and cutbacks summed over the increments.
struct IterationTotals {
  long newton = 0;
  int cutbacks = 0;
  long linear = 0;
  int linear_max = 0;
  long tangents = 0;
};

IterationTotals iteration_totals(const ElastoplasticResult& r) {
  IterationTotals t;
  for (const IncrementRecord& inc : r.increments) {
    t.newton += inc.newton.iterations;
    t.cutbacks += inc.cutbacks;
    t.linear += inc.newton.linear_iterations;
    t.tangents += inc.newton.tangents;
    t.linear_max = std::max(t.linear_max, inc.newton.linear_iterations_max);
  }
  return t;
}

/// history.csv: one row per converged increment, increment 0 the unloaded state.
void write_history(const spec::ProblemSpec& spec, const ElastoplasticResult& r,
                   io::OutputDirectory& out) {
  io::History history({"increment", "step", "step_fraction"});
  for (const auto& bc : spec.galerkin().boundary) history.add_column("factor_" + bc.name);
  for (const auto& bc : spec.galerkin().boundary) {
    const std::string kind = bc.constrains ? "reaction_" : "load_";
    history.add_column(kind + bc.name + "_x");
    history.add_column(kind + bc.name + "_y");
  }
  for (const auto& mon : spec.galerkin().gauges) {
    history.add_column("ux_" + mon.name);
    history.add_column("uy_" + mon.name);
  }
  for (const char* c : {"max_plastic_strain", "plastic_points", "newton_iterations", "cutbacks",
                        "residual_relative", "equilibrium_error"})
    history.add_column(c);
  for (std::size_t i = 0; i < r.increments.size(); ++i) {
    const IncrementRecord& inc = r.increments[i];
    std::vector<double> row{static_cast<double>(i), static_cast<double>(inc.step),
                            inc.step_fraction};
    for (std::size_t c = 0; c < spec.galerkin().boundary.size(); ++c) row.push_back(inc.factors[c]);
    for (const auto& b : inc.boundary) row.insert(row.end(), {b.force.x(), b.force.y()});
    for (const auto& u : inc.monitor_u) row.insert(row.end(), {u.x(), u.y()});
    const double rel = inc.newton.residual.empty()
                           ? 0.0
                           : inc.newton.residual.back() / std::max(inc.newton.scale.back(), 1e-300);
    row.insert(row.end(), {inc.max_plastic_strain, static_cast<double>(inc.plastic_points),
                           static_cast<double>(inc.newton.iterations),
                           static_cast<double>(inc.cutbacks), rel, inc.equilibrium_error});
    history.append(std::move(row));
  }
  history.write(out);
}

/// line_<name>.csv: the sampled lines at every increment.
void write_lines(const ElastoplasticResult& r, io::OutputDirectory& out) {
  for (const auto& [name, line_rows] : r.lines)
    out.write_csv("line_" + name + ".csv",
                  {"increment", "s", "x", "y", "ux", "uy", "stress_xx", "stress_yy", "stress_xy"},
                  line_rows);
}

/// The counts, memory, solver and Newton time sections of summary.json.
void describe_run(const spec::ProblemSpec& spec, const ElastoplasticResult& r,
                  io::Summary& summary) {
  const IterationTotals totals = iteration_totals(r);
  const int increments = static_cast<int>(r.increments.size()) - 1;
  summary.section("counts")
      .set("nodes", r.nodes)
      .set("dofs", r.dofs)
      .set("background_cells", r.cells)
      .set("domain_points", r.domain_points)
      .set("boundary_points", r.boundary_points)
      .set("matrix_nonzeros", r.matrix_nonzeros)
      .set("increments", increments)
      .set("newton_iterations", totals.newton)
      .set("cutbacks", totals.cutbacks);
  summary.section("memory")
      .set("peak_bytes_largest_rank", r.memory.largest_rank)
      .set("peak_bytes_all_ranks", r.memory.all_ranks);
  summary.section("solver")
      .set("type", r.solver)
      .set("tolerance", spec.galerkin().nonlinear.tolerance)
      .set("keep_tangent", spec.galerkin().nonlinear.keep_tangent)
      .set("tangents", totals.tangents)
      .set("linear_iterations", totals.linear)
      .set("linear_iterations_max_per_solve", totals.linear_max);
  double newton_s = 0.0;
  for (const auto& [name, sec] : r.timer.phases())
    if (name == "newton") newton_s = sec;
  io::Json newton_parts;
  newton_parts.set("residual_and_return_mapping", r.residual_seconds)
      .set("jacobian_assembly", r.jacobian_seconds)
      .set("linear_solves_and_other", newton_s - r.residual_seconds - r.jacobian_seconds);
  summary.section("time_s").set("newton_parts", newton_parts);
}

io::Json peak_json(const PeakStress& p) {
  io::Json j;
  j.set("max_von_mises_at_first_step_end", p.von_mises)
      .set("at", std::vector<double>{p.at.x(), p.at.y()})
      .set("fraction_of_first_step", p.fraction);
  return j;
}

/// results.elastic_limit: the first yield's load factors, forces and peak stresses, or why the
/// search was skipped.
io::Json elastic_limit_json(const spec::ProblemSpec& spec, const ElasticLimit& e) {
  auto& galerkin = spec.galerkin();
  io::Json limit;
  if (!e.skipped.empty()) limit.set("skipped", e.skipped);
  io::Json lim_factors, lim_forces;
  for (std::size_t c = 0; c < galerkin.boundary.size() && e.skipped.empty(); ++c) {
    lim_factors.set(galerkin.boundary[c].name, e.factors[c]);
    lim_forces.set(galerkin.boundary[c].name,
                   std::vector<double>{e.boundary[c].force.x(), e.boundary[c].force.y()});
  }
  if (e.skipped.empty())
    limit.set("fraction_of_first_step", e.fraction)
        .set("factors", lim_factors)
        .set("forces", lim_forces)
        .set("gauss_points", peak_json(e.gauss_points))
        .set("nodes", peak_json(e.nodes));
  return limit;
}

/// results.final: the last converged increment.
io::Json final_json(const spec::ProblemSpec& spec, const IncrementRecord& fin) {
  auto& galerkin = spec.galerkin();
  io::Json fin_factors, fin_forces, fin_monitors;
  for (std::size_t c = 0; c < galerkin.boundary.size(); ++c) {
    fin_factors.set(galerkin.boundary[c].name, fin.factors[c]);
    fin_forces.set(galerkin.boundary[c].name,
                   std::vector<double>{fin.boundary[c].force.x(), fin.boundary[c].force.y()});
  }
  for (std::size_t k = 0; k < galerkin.gauges.size() && k < fin.monitor_u.size(); ++k)
    fin_monitors.set(galerkin.gauges[k].name,
                     std::vector<double>{fin.monitor_u[k].x(), fin.monitor_u[k].y()});
  io::Json last;
  last.set("factors", fin_factors)
      .set("forces", fin_forces)
      .set("monitors", fin_monitors)
      .set("max_plastic_strain", fin.max_plastic_strain)
      .set("plastic_points", fin.plastic_points)
      .set("equilibrium_error", fin.equilibrium_error);
  return last;
}

/// results.steps: per load step, the increments planned and done and their Newton iterations.
io::Json steps_json(const spec::ProblemSpec& spec, const ElastoplasticResult& r) {
  auto& galerkin = spec.galerkin();
  io::Json steps;
  for (std::size_t s = 0; s < galerkin.steps.size(); ++s) {
    std::vector<double> its;
    for (const auto& inc : r.increments)
      if (&inc != &r.increments.front() && inc.step == static_cast<int>(s))
        its.push_back(inc.newton.iterations);
    io::Json js;
    js.set("increments_planned", galerkin.steps[s].increments)
        .set("increments_done", static_cast<int>(its.size()))
        .set("newton_iterations", its);
    steps.set(galerkin.steps[s].name, js);
  }
  return steps;
}

void write_summary(const spec::ProblemSpec& spec, const ElastoplasticResult& r,
                   const solvers::PetscSession& session, io::OutputDirectory& out) {
  io::Summary summary({spec.name, spec.description, spec.units, "elastoplastic_static", r.method});
  summary.set_status(r.status, r.stop_reason);
  summary.set("mpi_ranks", session.size()).set("openmp_threads", omp_get_max_threads());
  describe_run(spec, r, summary);
  io::Json& results = summary.section("results");
  results.set("elastic_limit", elastic_limit_json(spec, r.elastic_limit));
  if (spec.galerkin().initial_stress)
    results.set(
        "initial_stress",
        io::Json().set("type", "geostatic").set("out_of_balance", r.initial_out_of_balance));
  results.set("final", final_json(spec, r.increments.back())).set("steps", steps_json(spec, r));
  if (r.adaptation) results.set("adaptivity", adaptation_json(spec, *r.adaptation, r.estimate));
  summary.section("checkpoints") = r.checkpoints.describe(r.timer.total());
  summary.write(out, r.timer);
}

} // namespace

void write_elastoplastic_outputs(const spec::ProblemSpec& spec, const ElastoplasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  write_history(spec, r, out);
  write_lines(r, out);
  if (r.adaptation)
    write_adaptation(spec, *r.adaptation, r.estimate, static_cast<long>(r.increments.size()) - 1,
                     out);
  write_summary(spec, r, session, out);
}

} // namespace mf::implicit
