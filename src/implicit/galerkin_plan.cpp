#include "meshfree/implicit/galerkin_plan.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/quadrature/integration_points.hpp"

namespace mf::implicit {

namespace {

void describe_fe_mesh(const spec::ProblemSpec& spec, std::ostream& os) {
  const fem::Mesh mesh = read_fe_mesh(spec);
  os << "  method: " << describe_method(spec.galerkin().discretisation, spec.domain) << "\n"
     << "  mesh: " << mesh.element_count() << " " << fem::element_name(mesh.type) << " elements, "
     << mesh.node_count() << " nodes (" << 2 * mesh.node_count() << " DOFs)\n"
     << "  memory: " << describe_bytes(bytes_per::galerkin_node * mesh.node_count())
     << " for the discretisation, besides " << describe_bytes(bytes_per::program)
     << " for the program\n";
}

void describe_meshfree_nodes(const spec::ProblemSpec& spec, std::ostream& os) {
  const auto& d = spec.galerkin().discretisation;
  const auto nodes = geometry::generate_nodes(spec.domain, d.spacing, d.refinement);
  const auto pts = quadrature::domain_points(
      spec.domain, d.cell_size, d.order, d.cut_levels,
      {d.spacing, d.refinement, d.cell_size / d.spacing, d.dilation.maxCoeff()}, d.cut_arcs);
  os << "  method: " << describe_method(spec.galerkin().discretisation, spec.domain) << "\n"
     << "  nodes: " << nodes.x.size() << " (" << 2 * nodes.x.size() << " DOFs)\n"
     << "  integration: " << pts.cell_count << " cells, " << pts.x.size() << " points\n"
     << "  memory: "
     << describe_bytes(bytes_per::galerkin_node_alone * nodes.x.size() +
                       bytes_per::galerkin_point * pts.x.size())
     << " for the discretisation, besides " << describe_bytes(bytes_per::program)
     << " for the program\n";
}

} // namespace

double estimated_nodes(const spec::ProblemSpec& spec) {
  const bool solid = spec.is_solid();
  const Vec2 size = spec.domain.bounds().size();
  const double h = (solid ? spec.solid().discretisation : spec.galerkin().discretisation).spacing;
  return (size.x() / h + 1.0) * (size.y() / h + 1.0) * (solid ? spec.solid().depth / h + 1.0 : 1.0);
}

void print_galerkin_plan(const spec::ProblemSpec& spec, std::ostream& os) {
  if (spec.is_solid()) return print_solid_plan(spec, os);
  auto& galerkin = spec.galerkin();
  if (galerkin.discretisation.method == spec::Method::Fem)
    describe_fe_mesh(spec, os);
  else
    describe_meshfree_nodes(spec, os);
  for (const auto& bc : galerkin.boundary) {
    double len = 0.0;
    for (const auto& p : spec::select_boundary(spec.domain, bc.on, bc.key_path)) len += p.length();
    os << "  boundary " << bc.name << ": " << (bc.constrains ? "displacement" : "traction")
       << " on length " << len << "\n";
  }
  for (const auto& step : galerkin.steps)
    os << "  step " << step.name << ": " << step.increments << " increments\n";
}

} // namespace mf::implicit
