#include "meshfree/implicit/model_problem_1d_output.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/io/results.hpp"

namespace mf::implicit {

void write_model_1d_outputs(const spec::ProblemSpec& spec, const Model1DResult& r,
                            io::OutputDirectory& out) {
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < r.x.size(); ++k)
    rows.push_back({r.x[k], r.y[k], r.y_exact[k], r.dy[k], r.dy_exact[k]});
  out.write_csv("line_solution.csv", {"x", "y", "y_exact", "dy_dx", "dy_dx_exact"}, rows);
  std::vector<Vec2> pts;
  for (std::size_t k = 0; k < r.x.size(); ++k) pts.emplace_back(r.x[k], 0.0);
  io::FieldOutput fields(&out, "fields", pts);
  fields.scalar("y", r.y);
  fields.scalar("y_exact", r.y_exact);
  fields.write(1.0);
  fields.close();
  io::History history({"step", "error_l2_relative", "error_h1_relative", "error_max_relative"});
  history.append({1.0, r.error_l2, r.error_h1, r.error_max});
  history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "model_problem_1d",
                       describe_method(spec.model_1d().discretisation, spec.domain)});
  summary.section("counts")
      .set("nodes", r.nodes)
      .set("quadrature_points", r.points)
      .set("dofs", r.nodes);
  summary.section("results")
      .set("error_l2_relative", r.error_l2)
      .set("error_h1_relative", r.error_h1)
      .set("error_max_relative", r.error_max);
  summary.write(out, r.timer);
}

} // namespace mf::implicit
