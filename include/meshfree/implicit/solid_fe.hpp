#pragma once
// Finite elements of a prism behind one interface, so that the 3D model (solid_model) holds
// bricks (solid_bricks.hpp) or tetrahedra (solid_tets.hpp) alike: every point of an element
// comes with its nodes' shape values, and physical gradients, in the compressed rows of
// SolidShapeTable, so that the 3D meshfree assembly, solvers and outputs serve them unchanged.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/spec/galerkin_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mf::implicit {

/// Points of the elements with their shape functions, in compressed rows (nodes increasing).
struct ElementPoints {
  SolidPoints points; // x, weight (volume or area), normal (face points)
  std::vector<int> offset{0};
  std::vector<int> node;
  std::vector<double> phi;
  std::vector<Vec3> dphi; // only for body points and shapes asked with gradients
};

class SolidElements {
public:
  virtual ~SolidElements() = default;

  virtual int node_count() const = 0;
  virtual const std::vector<Vec3>& nodes() const = 0;
  virtual int element_count() const = 0;
  virtual int nodes_per_element() const = 0;
  /// "hex8", "hex20", "tet4" or "tet10".
  virtual const char* name() const = 0;
  /// The elements and nodes for `meshfree check`: "bricks: 40 of 20 nodes, 301 nodes (3 layers
  /// along z)".
  virtual std::string summary() const = 0;
  /// The quadrature order used when discretisation.fem.order is not given.
  virtual int default_order() const = 0;

  /// Every element's integration points with shapes and gradients (bricks: order^3 Gauss
  /// points; tetrahedra: the rule exact to degree `order`).
  virtual ElementPoints body_points(int order) const = 0;
  /// Integration points of the named faces, within `box` when given.
  virtual ElementPoints face_points(const std::vector<std::string>& faces, int order,
                                    const std::optional<spec::Box>& box) const = 0;
  /// The shapes (values, and gradients if asked) at points of the body; throws naming a point
  /// no element holds.
  virtual ElementPoints shapes_at(const std::vector<Vec3>& x, bool gradients = false) const = 0;
};

/// The elements `d.fem.element` asks for on the prism: hex8 or hex20 bricks (the section's q4 or
/// q8 mesh extruded), tet4 or tet10 meshed by gmsh.
std::unique_ptr<SolidElements> make_solid_elements(const spec::DiscretisationSpec& d,
                                                   const geometry::Prism& body);

/// The rows of `all` (face points, `per_face` a face in a row) whose points lie within `tol` of
/// `box`. A face partly inside the box is refused, since its Gauss points would load a part of
/// it that is not the box's: the box's edges must follow element borders (`nodes`: the mesh's
/// node positions, from which each face's extent is read).
ElementPoints points_in_box(const ElementPoints& all, const spec::Box& box, double tol,
                            int per_face, const std::vector<Vec3>& nodes);

} // namespace mf::implicit
