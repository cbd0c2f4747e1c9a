#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/results.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::implicit {

void write_elastoplastic_outputs(const io::ProblemSpec& spec, const ElastoplasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  // history.csv: one row per converged increment, increment 0 the unloaded state.
  io::History history({"increment", "step", "step_fraction"});
  for (const auto& bc : spec.boundary) history.add_column("factor_" + bc.name);
  for (const auto& bc : spec.boundary) {
    const std::string kind = bc.constrains ? "reaction_" : "load_";
    history.add_column(kind + bc.name + "_x");
    history.add_column(kind + bc.name + "_y");
  }
  for (const auto& mon : spec.gauges) {
    history.add_column("ux_" + mon.name);
    history.add_column("uy_" + mon.name);
  }
  for (const char* c : {"max_plastic_strain", "plastic_points", "newton_iterations", "cutbacks",
                        "residual_relative", "equilibrium_error"})
    history.add_column(c);
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
    history.append(std::move(row));
    newton_total += inc.newton.iterations;
    cut_total += inc.cutbacks;
  }
  history.write(out);
  for (const auto& [name, line_rows] : r.lines)
    out.write_csv("line_" + name + ".csv",
                  {"increment", "s", "x", "y", "ux", "uy", "stress_xx", "stress_yy", "stress_xy"},
                  line_rows);

  io::Summary summary({spec.name, spec.description, spec.units, "elastoplastic_static", r.method});
  summary.set_status(r.status, r.stop_reason);
  summary.set("mpi_ranks", session.size()).set("openmp_threads", omp_get_max_threads());
  const int increments = static_cast<int>(r.increments.size()) - 1;
  summary.section("counts")
      .set("nodes", r.nodes)
      .set("dofs", r.dofs)
      .set("background_cells", r.cells)
      .set("domain_points", r.domain_points)
      .set("boundary_points", r.boundary_points)
      .set("matrix_nonzeros", r.matrix_nonzeros)
      .set("increments", increments)
      .set("newton_iterations", newton_total)
      .set("cutbacks", cut_total);
  long linear_total = 0;
  int linear_max = 0;
  for (const IncrementRecord& rec : r.increments) {
    linear_total += rec.newton.linear_iterations;
    linear_max = std::max(linear_max, rec.newton.linear_iterations_max);
  }
  summary.section("memory")
      .set("peak_bytes_largest_rank", r.memory.largest_rank)
      .set("peak_bytes_all_ranks", r.memory.all_ranks);
  summary.section("solver")
      .set("type", r.solver)
      .set("tolerance", spec.nonlinear.tolerance)
      .set("linear_iterations", linear_total)
      .set("linear_iterations_max_per_solve", linear_max);
  double newton_s = 0.0;
  for (const auto& [name, sec] : r.timer.phases())
    if (name == "newton") newton_s = sec;
  io::Json newton_parts;
  newton_parts.set("residual_and_return_mapping", r.residual_seconds)
      .set("jacobian_assembly", r.jacobian_seconds)
      .set("linear_solves_and_other", newton_s - r.residual_seconds - r.jacobian_seconds);
  summary.section("time_s").set("newton_parts", newton_parts);

  io::Json limit, last, steps;
  const ElasticLimit& e = r.elastic_limit;
  if (!e.skipped.empty()) limit.set("skipped", e.skipped);
  io::Json lim_factors, lim_forces;
  for (std::size_t c = 0; c < spec.boundary.size() && e.skipped.empty(); ++c) {
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
  if (e.skipped.empty())
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
  io::Json& results = summary.section("results");
  results.set("elastic_limit", limit);
  if (spec.initial_stress)
    results.set(
        "initial_stress",
        io::Json().set("type", "geostatic").set("out_of_balance", r.initial_out_of_balance));
  results.set("final", last).set("steps", steps);
  summary.section("checkpoints") = r.checkpoints.describe(r.timer.total());
  summary.write(out, r.timer);
}

} // namespace mf::implicit
