#include "meshfree/implicit/model_problem_1d_output.hpp"
#include "meshfree/implicit/galerkin_model.hpp"

namespace mf::implicit {

void write_model_1d_outputs(const io::ProblemSpec& spec, const Model1DResult& r,
                            io::OutputDirectory& out) {
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < r.x.size(); ++k)
    rows.push_back({r.x[k], r.y[k], r.y_exact[k], r.dy[k], r.dy_exact[k]});
  out.write_csv("line_solution.csv", {"x", "y", "y_exact", "dy_dx", "dy_dx_exact"}, rows);
  std::vector<Vec2> pts;
  std::vector<double> y, ye;
  for (std::size_t k = 0; k < r.x.size(); ++k) pts.emplace_back(r.x[k], 0.0);
  io::FieldStep step;
  step.time = 1.0;
  step.scalars = {{"y", r.y}, {"y_exact", r.y_exact}};
  out.write_fields(pts, {step});
  out.write_csv("history.csv",
                {"step", "error_l2_relative", "error_h1_relative", "error_max_relative"},
                {{1.0, r.error_l2, r.error_h1, r.error_max}});
  io::Json counts, times, results;
  counts.set("nodes", r.nodes).set("quadrature_points", r.points).set("dofs", r.nodes);
  for (const auto& [name, sec] : r.timer.phases()) times.set(name, sec);
  times.set("total", r.timer.total());
  results.set("error_l2_relative", r.error_l2)
      .set("error_h1_relative", r.error_h1)
      .set("error_max_relative", r.error_max);
  io::Json summary;
  summary.set("problem", spec.name)
      .set("description", spec.description)
      .set("analysis", "model_problem_1d")
      .set("method", describe_method(spec.discretisation))
      .set("status", "completed")
      .set("counts", counts)
      .set("time_s", times)
      .set("results", results);
  out.write_text("summary.json", summary.str() + "\n");
}

} // namespace mf::implicit
