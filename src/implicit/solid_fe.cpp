#include "meshfree/implicit/solid_fe.hpp"
#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/solid_bricks.hpp"
#include "meshfree/implicit/solid_tets.hpp"

namespace mf::implicit {

std::unique_ptr<SolidElements> make_solid_elements(const spec::DiscretisationSpec& d,
                                                   const geometry::Prism& body) {
  const std::string& e = d.fem.element;
  if (e == "tet4" || e == "tet10") {
    fem::TetMesh mesh = fem::mesh_prism(body, d.spacing, d.refinement, e == "tet10");
    fem::sort_nodes_for_locality(mesh, fem::characteristic_size(mesh));
    return std::make_unique<TetElements>(std::move(mesh), body);
  }
  return std::make_unique<ExtrudedMesh>(plane_fe_mesh(d, body.section), body, d.spacing);
}

ElementPoints points_in_box(const ElementPoints& all, const spec::Box& box, double tol) {
  ElementPoints kept;
  for (std::size_t r = 0; r < all.points.x.size(); ++r) {
    if (!box.contains(all.points.x[r], tol)) continue;
    kept.points.x.push_back(all.points.x[r]);
    kept.points.weight.push_back(all.points.weight[r]);
    if (!all.points.normal.empty()) kept.points.normal.push_back(all.points.normal[r]);
    const auto from = all.offset[r], to = all.offset[r + 1];
    kept.node.insert(kept.node.end(), all.node.begin() + from, all.node.begin() + to);
    kept.phi.insert(kept.phi.end(), all.phi.begin() + from, all.phi.begin() + to);
    if (!all.dphi.empty())
      kept.dphi.insert(kept.dphi.end(), all.dphi.begin() + from, all.dphi.begin() + to);
    kept.offset.push_back(static_cast<int>(kept.node.size()));
  }
  return kept;
}

} // namespace mf::implicit
