#pragma once
// Finite elements of a prism: the plane body's Q4 or Q8 mesh (the mesh a plane FE run makes of
// the same geometry, refinement boxes in its plane) extruded in layers along z (the base layers
// and, over a refinement box's range, the box's: implicit/prism_levels; an extruded mesh refines
// along z through the whole section) into 8-node or 20-node serendipity bricks
// (Zienkiewicz & Taylor, The Finite Element Method, vol. 1, 6th ed., sec. 6.5). Every point of a
// brick is given by its plane element's natural (xi, eta), its layer and zeta in [-1, 1]; the
// brick's shape functions and physical gradients there come in the compressed rows of
// SolidShapeTable (solid_fe.hpp), so that the 3D meshfree assembly serves the bricks unchanged. The
// isoparametric brick map equals the extrusion of the plane element's map (the serendipity brick's
// space holds the Q8 space times linear functions of zeta), so curved Q8 edges on holes carry over.
#include "meshfree/core/types.hpp"
#include "meshfree/fem/mesh.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/implicit/prism_levels.hpp"
#include "meshfree/implicit/solid_fe.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::implicit {

class ExtrudedMesh final : public SolidElements {
public:
  /// The plane mesh (Q4 or Q8) in the prism's layers for nodes `spacing` apart with the
  /// refinement boxes.
  ExtrudedMesh(fem::Mesh plane, const geometry::Prism& body, double spacing,
               const std::vector<geometry::Refinement>& refinement);

  int node_count() const override { return static_cast<int>(x_.size()); }
  const std::vector<Vec3>& nodes() const override { return x_; }
  int element_count() const override { return plane_.element_count() * layer_count(); }
  int nodes_per_element() const override { return serendipity() ? 20 : 8; }
  const char* name() const override { return serendipity() ? "hex20" : "hex8"; }
  std::string summary() const override;
  /// 3 x 3 x 3 Gauss points for 20-node bricks, 2 x 2 x 2 for 8-node ones.
  int default_order() const override { return serendipity() ? 3 : 2; }
  bool serendipity() const { return plane_.type == fem::ElementType::Q8; }

  /// Every brick's order^3 Gauss points with shapes and gradients.
  ElementPoints body_points(int order) const override;
  /// Gauss points (`order` per direction) of the named faces, within `box` when given.
  ElementPoints face_points(const std::vector<std::string>& faces, int order,
                            const std::optional<spec::Box>& box) const override;
  ElementPoints shapes_at(const std::vector<Vec3>& x, bool gradients = false) const override;

private:
  /// The brick of plane element e in layer l: its nodes, and each node's natural coordinates.
  void brick(int e, int l, int* nodes, Vec3* natural) const;
  /// Appends the point (xi, eta, zeta) of brick (e, l) to `out`, with weight `w` times its
  /// volume (face: its area) measure and, for a face point, the outward normal.
  void add_point(int e, int l, const Vec3& xi, double w, int face, bool gradients,
                 ElementPoints& out) const;

  int layer_count() const { return static_cast<int>(layers_.size()); }

  fem::Mesh plane_;
  geometry::Prism body_;
  std::vector<Slab> layers_;
  std::vector<int> corner_index_; // plane node -> its vertical mid-edge column (Q8), or -1
  int corners_ = 0;
  std::vector<Vec3> x_;
};

} // namespace mf::implicit
