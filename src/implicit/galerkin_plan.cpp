#include "meshfree/implicit/galerkin_plan.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <iomanip>

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
  if (const auto& a = d.adapt)
    os << "  adapt: these nodes refined until the estimated error is at most " << a->target
       << " (at most " << a->passes << " pilot solves, " << a->max_nodes
       << " nodes; an elastoplastic pilot takes at most " << a->pilot_increments
       << " increments a step), then the analysis on the last cloud\n";
}

/// The area of a plane body, integrated on cells of a 64th of its bounding box, cut cells split
/// four levels deep: within about 1e-4 of the exact area.
double body_area(const geometry::Domain& domain) {
  const quadrature::DomainPoints fine =
      quadrature::domain_points(domain, domain.bounds().size().maxCoeff() / 64.0, 2, 4);
  double area = 0.0;
  for (const double w : fine.weight) area += w;
  return area;
}

/// The body as the user described it: its area and the length of each named piece of its
/// boundary, in the order they come; a geometry file's parts with their areas and materials.
void describe_body(const spec::ProblemSpec& spec, std::ostream& os) {
  const geometry::Domain& domain = spec.domain;
  const BoundingBox bb = domain.bounds();
  const double area = body_area(domain);
  std::vector<std::pair<std::string, double>> pieces;
  for (const geometry::Curve& c : domain.boundary()) {
    auto at = std::find_if(pieces.begin(), pieces.end(),
                           [&](const auto& p) { return p.first == c.name; });
    if (at == pieces.end()) at = pieces.insert(pieces.end(), {c.name, 0.0});
    at->second += c.length();
  }
  os << "  body: area " << std::setprecision(6) << area << ", in the box " << bb.size().x() << " x "
     << bb.size().y() << "; boundary pieces (length):";
  for (const auto& [name, length] : pieces) os << " " << name << " " << length;
  os << "\n" << std::setprecision(6);
  for (const spec::MaterialRegion& r : spec.galerkin().material_regions)
    if (r.region.part)
      os << "  " << r.key_path << ": area " << body_area(*r.region.part) << ", material "
         << spec.materials[r.material].name << "\n";
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
  describe_body(spec, os);
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

/// Each increment is a Newton solve over every degree of freedom that writes a field frame, a
/// Gauss-point frame and a display-mesh frame, about 700 bytes per node together (measured on
/// plate_plastic_thesis, README.md "Running").
void require_increment_output(const spec::ProblemSpec& spec, const std::string& folder) {
  const auto& steps = spec.is_solid() ? spec.solid().steps : spec.galerkin().steps;
  const double nodes = estimated_nodes(spec);
  const std::size_t listed = spec.is_galerkin() && spec.galerkin().initial_stress; // "geostatic"
  double frames = 1.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    frames += steps[k].increments;
    if (k < listed) continue;
    const std::string key = "steps[" + std::to_string(k - listed) + "].increments";
    require_run_time(key, "DOF-increments of the schedule so far", frames * 2.0 * nodes,
                     work_per_second::galerkin_dof_increments);
    require_disk(key, "field frames of the schedule so far", frames, 700.0 * nodes, folder);
  }
}

} // namespace mf::implicit
