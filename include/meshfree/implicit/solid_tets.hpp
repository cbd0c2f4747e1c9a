#pragma once
// Tetrahedra of a prism: gmsh's 4- or 10-node tetrahedra of the body (fem::mesh_prism), each
// boundary triangle named after the prism face it lies on (its corners on a side face's edge or
// hole, or on the plane z0 or z0 + depth), with their integration points and shape functions in
// the compressed rows of SolidShapeTable (solid_fe.hpp). Body points: the tetrahedron rule exact
// to degree `order` (default 1 for tet4, whose strains are constant, and 2 for tet10, whose
// stiffness integrand is quadratic on a straight-sided element); face points: the triangle rule
// exact to degree max(order, 2p), p the element's degree, so that the penalty's N_a N_b is
// integrated exactly on flat faces.
#include "meshfree/fem/tet_locator.hpp"
#include "meshfree/fem/tetrahedra.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/implicit/solid_fe.hpp"
#include <memory>
#include <string>
#include <vector>

namespace mf::implicit {

class TetElements final : public SolidElements {
public:
  /// Error naming a boundary triangle that lies on no face of the prism.
  TetElements(fem::TetMesh mesh, const geometry::Prism& body);
  TetElements(const TetElements&) = delete; // the locator points to the mesh
  TetElements& operator=(const TetElements&) = delete;

  int node_count() const override { return mesh_.node_count(); }
  const std::vector<Vec3>& nodes() const override { return mesh_.x; }
  int element_count() const override { return mesh_.element_count(); }
  int nodes_per_element() const override { return mesh_.nodes_per_element(); }
  const char* name() const override { return mesh_.quadratic ? "tet10" : "tet4"; }
  std::string summary() const override;
  int default_order() const override { return mesh_.quadratic ? 2 : 1; }
  const fem::TetMesh& mesh() const { return mesh_; }

  ElementPoints body_points(int order) const override;
  ElementPoints face_points(const std::vector<std::string>& faces, int order,
                            const std::optional<spec::Box>& box) const override;
  ElementPoints shapes_at(const std::vector<Vec3>& x, bool gradients = false) const override;

private:
  /// Appends the point xi of element e to `out`, with weight `w` times its volume measure (on
  /// local face `face` >= 0: its area measure, and the outward normal).
  void add_point(int e, const Vec3& xi, double w, int face, bool gradients,
                 ElementPoints& out) const;
  /// The prism face (an index into names_) that boundary triangle f lies on, or -1.
  int face_of(const fem::TetFace& f, double tol) const;

  fem::TetMesh mesh_;
  geometry::Prism body_;
  std::vector<std::string> names_; // the prism's face names
  std::vector<fem::TetFace> boundary_;
  std::vector<int> boundary_name_; // the index into names_ of each boundary triangle
  std::unique_ptr<fem::TetLocator> locator_;
};

} // namespace mf::implicit
