#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

namespace {

quadrature::CellSizing sizing_of(const spec::DiscretisationSpec& d) {
  return {d.spacing, d.refinement, d.cell_size / d.spacing, d.dilation.maxCoeff()};
}

/// Points (z, weight) of `order` Gauss points in each of the body's layers.
std::vector<std::pair<double, double>> through_depth(const geometry::Prism& body, double spacing,
                                                     int order) {
  const int layers = layer_count(body, spacing);
  const double dz = body.depth / layers;
  const GaussRule& g = gauss_legendre(order);
  std::vector<std::pair<double, double>> out;
  for (int l = 0; l < layers; ++l)
    for (std::size_t q = 0; q < g.points.size(); ++q)
      out.emplace_back(body.z0 + (l + 0.5 * (g.points[q] + 1.0)) * dz, 0.5 * dz * g.weights[q]);
  return out;
}

bool kept(const std::optional<spec::Box>& box, const Vec3& x, double tol) {
  return !box || box->contains(x, tol);
}

} // namespace

int layer_count(const geometry::Prism& body, double spacing) {
  return std::max(1, static_cast<int>(std::lround(body.depth / spacing)));
}

SolidNodes prism_nodes(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  const geometry::NodeCloud plane = geometry::generate_nodes(body.section, d.spacing, d.refinement);
  const int layers = layer_count(body, d.spacing);
  const double dz = body.depth / layers;
  SolidNodes n;
  // Layer-major order: contiguous ranges of nodes are slabs, which keeps the partition over
  // ranks compact.
  for (int l = 0; l <= layers; ++l) {
    const double end = (l == 0 || l == layers) ? 0.5 : 1.0;
    for (std::size_t i = 0; i < plane.x.size(); ++i) {
      n.x.emplace_back(plane.x[i].x(), plane.x[i].y(), body.z0 + l * dz);
      n.spacing.push_back(std::max(plane.spacing[i], dz));
      n.volume.push_back(plane.volume[i] * dz * end);
    }
  }
  return n;
}

SolidPoints prism_volume_points(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  const quadrature::DomainPoints plane = quadrature::domain_points(
      body.section, d.cell_size, d.order, d.cut_levels, sizing_of(d), d.cut_arcs);
  SolidPoints p;
  for (const auto& [z, wz] : through_depth(body, d.cell_size, d.order))
    for (std::size_t k = 0; k < plane.x.size(); ++k) {
      p.x.emplace_back(plane.x[k].x(), plane.x[k].y(), z);
      p.weight.push_back(plane.weight[k] * wz);
    }
  return p;
}

SolidPoints prism_face_points(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                              const std::vector<std::string>& faces,
                              const std::optional<spec::Box>& box) {
  const double tol = 1e-9 * std::max(body.depth, body.section.bounds().size().maxCoeff());
  const auto named = [&faces](const std::string& n) {
    return std::find(faces.begin(), faces.end(), n) != faces.end();
  };
  SolidPoints p;
  const auto add = [&](const Vec3& x, double w, const Vec3& n) {
    if (!kept(box, x, tol)) return;
    p.x.push_back(x);
    p.weight.push_back(w);
    p.normal.push_back(n);
  };
  std::vector<geometry::Curve> sides;
  for (const geometry::Curve& c : body.section.boundary())
    if (named(c.name)) sides.push_back(c);
  if (!sides.empty()) {
    const quadrature::BoundaryPoints edge =
        quadrature::boundary_points(sides, d.cell_size, d.boundary_order, sizing_of(d));
    for (const auto& [z, wz] : through_depth(body, d.cell_size, d.boundary_order))
      for (std::size_t k = 0; k < edge.x.size(); ++k)
        add(Vec3(edge.x[k].x(), edge.x[k].y(), z), edge.weight[k] * wz,
            Vec3(edge.normal[k].x(), edge.normal[k].y(), 0.0));
  }
  for (const bool back : {true, false}) {
    if (!named(back ? "back" : "front")) continue;
    const quadrature::DomainPoints end = quadrature::domain_points(
        body.section, d.cell_size, d.boundary_order, d.cut_levels, sizing_of(d), d.cut_arcs);
    const double z = back ? body.z0 : body.z1();
    for (std::size_t k = 0; k < end.x.size(); ++k)
      add(Vec3(end.x[k].x(), end.x[k].y(), z), end.weight[k], Vec3(0.0, 0.0, back ? -1.0 : 1.0));
  }
  return p;
}

} // namespace mf::implicit
