#include "meshfree/app/elastic_static.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/elastic_output.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <iostream>

namespace mf::app {

implicit::ElasticResult elastic_static(const io::ProblemSpec& spec,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory* out) {
  // The display mesh on every rank alike (its nodal average is collective; `out` is rank 0's).
  implicit::ElasticResult r = implicit::solve_elastic_static(spec, session, true);
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) implicit::write_elastic_outputs(spec, r, session, *out);
  }
  return r;
}

namespace {

void describe_fe_mesh(const io::ProblemSpec& spec) {
  const fem::Mesh mesh = implicit::read_fe_mesh(spec);
  std::cout << "  method: " << implicit::describe_method(spec) << "\n"
            << "  mesh: " << mesh.element_count() << " " << fem::element_name(mesh.type)
            << " elements, " << mesh.node_count() << " nodes (" << 2 * mesh.node_count()
            << " DOFs)\n"
            << "  memory: " << describe_bytes(bytes_per::galerkin_node * mesh.node_count())
            << " for the discretisation, besides " << describe_bytes(bytes_per::program)
            << " for the program\n";
}

void describe_meshfree_nodes(const io::ProblemSpec& spec) {
  const auto& d = spec.discretisation;
  const auto nodes = geometry::generate_nodes(spec.domain, d.spacing, d.refinement);
  const auto pts = quadrature::domain_points(
      spec.domain, d.cell_size, d.order, d.cut_levels,
      {d.spacing, d.refinement, d.cell_size / d.spacing, d.dilation.maxCoeff()}, d.cut_arcs);
  std::cout << "  method: " << implicit::describe_method(spec) << "\n"
            << "  nodes: " << nodes.x.size() << " (" << 2 * nodes.x.size() << " DOFs)\n"
            << "  integration: " << pts.cell_count << " cells, " << pts.x.size() << " points\n"
            << "  memory: "
            << describe_bytes(bytes_per::galerkin_node_alone * nodes.x.size() +
                              bytes_per::galerkin_point * pts.x.size())
            << " for the discretisation, besides " << describe_bytes(bytes_per::program)
            << " for the program\n";
}

RunOutcome run(const RunRequest& q) {
  log_phases(elastic_static(q.spec, q.session, q.out).timer);
  return {};
}

} // namespace

void describe_galerkin(const io::ProblemSpec& spec) {
  if (spec.discretisation.method == io::Method::Fem)
    describe_fe_mesh(spec);
  else
    describe_meshfree_nodes(spec);
  for (const auto& bc : spec.boundary) {
    double len = 0.0;
    for (const auto& p : io::select_boundary(spec.domain, bc.on, bc.key_path)) len += p.length();
    std::cout << "  boundary " << bc.name << ": " << (bc.constrains ? "displacement" : "traction")
              << " on length " << len << "\n";
  }
  for (const auto& step : spec.steps)
    std::cout << "  step " << step.name << ": " << step.increments << " increments\n";
}

void admit_galerkin(const io::ProblemSpec& spec, const std::string&) {
  if (spec.discretisation.method == io::Method::Fem) implicit::read_fe_mesh(spec);
}

AnalysisEntry elastic_static_entry() {
  AnalysisEntry e{io::Analysis::ElasticStatic, "elastic_static"};
  e.describe = describe_galerkin;
  e.check = describe_galerkin;
  e.admit = admit_galerkin;
  e.run = run;
  return e;
}

} // namespace mf::app
