#include "meshfree/implicit/solid_fe.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/solid_bricks.hpp"
#include "meshfree/implicit/solid_tets.hpp"
#include <cmath>
#include <limits>
#include <utility>

namespace mf::implicit {

std::unique_ptr<SolidElements> make_solid_elements(const spec::DiscretisationSpec& d,
                                                   const geometry::Prism& body) {
  const std::string& e = d.fem.element;
  if (e == "tet4" || e == "tet10") {
    fem::TetMesh mesh = fem::mesh_prism(body, d.spacing, d.refinement, e == "tet10");
    fem::sort_nodes_for_locality(mesh, fem::characteristic_size(mesh));
    return std::make_unique<TetElements>(std::move(mesh), body);
  }
  spec::DiscretisationSpec plane = d; // the section's mesh, of the plane element of the bricks
  plane.fem.element = spec::plane_element(e);
  return std::make_unique<ExtrudedMesh>(plane_fe_mesh(plane, body.section), body, d.spacing,
                                        d.refinement);
}

namespace {

/// The box of the nodes that carry a face's points (those with a shape function not zero there;
/// the others vanish on the face).
std::pair<Vec3, Vec3> face_extent(const ElementPoints& all, std::size_t first, int count,
                                  const std::vector<Vec3>& nodes) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t r = first; r < first + count; ++r)
    for (int j = all.offset[r]; j < all.offset[r + 1]; ++j)
      if (std::abs(all.phi[j]) > 1e-12) {
        lo = lo.cwiseMin(nodes[all.node[j]]);
        hi = hi.cwiseMax(nodes[all.node[j]]);
      }
  return {lo, hi};
}

/// Whether the box holds a part of positive area of a face with extent [lo, hi], but not all.
bool box_cuts(const Vec3& lo, const Vec3& hi, const spec::Box& box, double tol) {
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    if (lo[a] < box.lo[a] - tol || hi[a] > box.hi[a] + tol) inside = false;
    const double common = std::min(hi[a], box.hi[a]) - std::max(lo[a], box.lo[a]);
    if (hi[a] - lo[a] <= tol ? common < -tol : common <= tol) return false;
  }
  return !inside;
}

} // namespace

ElementPoints points_in_box(const ElementPoints& all, const spec::Box& box, double tol,
                            int per_face, const std::vector<Vec3>& nodes) {
  ElementPoints kept;
  const std::size_t n = all.points.x.size();
  MF_ASSERT(per_face > 0 && n % per_face == 0);
  for (std::size_t first = 0; first < n; first += per_face) {
    const auto [lo, hi] = face_extent(all, first, per_face, nodes);
    MF_REQUIRE(!box_cuts(lo, hi, box, tol), "the box cuts the element face from (", lo.x(), ", ",
               lo.y(), ", ", lo.z(), ") to (", hi.x(), ", ", hi.y(), ", ", hi.z(),
               "): a box's edges must lie on element borders");
    for (std::size_t r = first; r < first + per_face; ++r) {
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
  }
  return kept;
}

} // namespace mf::implicit
