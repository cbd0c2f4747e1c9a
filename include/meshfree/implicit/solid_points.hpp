#pragma once
// Nodes and integration points of a prism (geometry::Prism), built from those of its plane
// section: the plane node cloud on levels along z, the plane background cells' Gauss points
// times a Gauss rule along z in each slab between levels (so the plane quadrature's exact cut
// cells of holes carry over to the cylindrical holes), and face points: a side face is its
// boundary piece's Gauss points times the rule along z, an end the plane body's points at z0 or
// z0 + depth. Refinement boxes refine along z too (implicit/prism_levels).
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/implicit/prism_levels.hpp"
#include "meshfree/spec/galerkin_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::implicit {

struct SolidNodes {
  std::vector<Vec3> x;
  std::vector<double> spacing; // local nominal spacing at each node
  std::vector<double> volume;  // nodal volume used by the RK construction
};

struct SolidPoints {
  std::vector<Vec3> x;
  std::vector<double> weight; // volume weight, or area weight on a face
  std::vector<Vec3> normal;   // outward unit normal (face points only)
  // The integration cell or element of each volume point (a refined piece of the plane's
  // background cell times a layer): the cells of the cell-mean volumetric strain.
  std::vector<int> cell;
};

/// The heights of the node levels: the base layers and each refinement box's.
std::vector<MergedLevel> node_levels(const geometry::Prism& body,
                                     const spec::DiscretisationSpec& d);

/// The plane section's node cloud (discretisation spacing, and the refinement boxes whose range
/// holds the level) at each level, each node on the levels of its own spacing.
SolidNodes prism_nodes(const geometry::Prism& body, const spec::DiscretisationSpec& d);

/// Gauss points of the body: the plane background cells' points (cell size, order, cut levels
/// and exact arcs of the discretisation) times `order` Gauss points in each layer.
SolidPoints prism_volume_points(const geometry::Prism& body, const spec::DiscretisationSpec& d);

/// Gauss points of the named faces, those within `box` (when given) kept.
SolidPoints prism_face_points(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                              const std::vector<std::string>& faces,
                              const std::optional<spec::Box>& box = std::nullopt);

} // namespace mf::implicit
