#pragma once
// Isoparametric elements: reference shape functions, quadrature rules, and the integration
// points of a mesh with shape values and physical gradients in the compressed-row layout of
// implicit::ShapeTable (offset / node / phi / dphi), so that one Galerkin assembly serves finite
// elements and meshfree shape functions alike. Also a point locator for sampling fields.
#include "meshfree/core/types.hpp"
#include "meshfree/fem/mesh.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include <vector>

namespace mf::fem {

constexpr int kMaxElementNodes = 8;

/// Reference-element shape functions N and natural derivatives dN/dxi at xi (arrays of
/// nodes_per_element entries; dN_dxi may be null). Reference elements: T3 the triangle
/// (0,0), (1,0), (0,1) with N = (1 - xi - eta, xi, eta); Q4 and Q8 the square [-1, 1]^2 with
/// corners (-1,-1), (1,-1), (1,1), (-1,1) (Zienkiewicz & Taylor, The Finite Element Method,
/// vol. 1, 6th ed., sec. 6.4 for the serendipity Q8).
void shape_functions(ElementType type, const Vec2& xi, double* N, Vec2* dN_dxi);

/// Natural coordinates of the element's nodes in local order.
const Vec2* reference_nodes(ElementType type);

/// Quadrature on the reference element; the weights sum to its area (T3 1/2, quads 4).
/// Quads: tensor Gauss-Legendre with `order` points per direction (order^2 points, exact for
/// degree 2 order - 1 in each variable). Triangles: `order` is the polynomial degree the rule
/// integrates exactly; degrees 1-5 use the symmetric rules with positive weights of Strang & Fix
/// (1973) and Dunavant (1985) (1, 3, 6, 6, 7 points), higher degrees a collapsed (Duffy)
/// tensor Gauss rule.
struct ReferenceRule {
  std::vector<Vec2> xi;
  std::vector<double> weight;
};
ReferenceRule domain_rule(ElementType type, int order);
/// Q8 3x3, Q4 2x2, T3 1 point (degree 1): exact stiffness on undistorted elements.
int default_order(ElementType type);
/// Gauss points per boundary edge that integrate a traction of the element's own degree against
/// the edge shape functions exactly on straight edges: T3/Q4 2, Q8 3.
int default_edge_order(ElementType type);

/// Points in physical space with the nodes that have a nonzero shape function there, sorted
/// increasingly (phi/dphi permuted with them); row r holds node/phi/dphi[offset[r] ..
/// offset[r + 1]).
struct PointShapes {
  std::vector<Vec2> x;
  std::vector<double> weight; // area weight w * det J; empty for shapes_at
  std::vector<int> element;
  std::vector<int> offset{0};
  std::vector<int> node;
  std::vector<double> phi;
  std::vector<Vec2> dphi; // dN/dx = J^{-T} dN/dxi; empty when gradients were not asked for
  int rows() const { return static_cast<int>(offset.size()) - 1; }
};

/// Every element's points of domain_rule(type, order), element by element. Error naming the
/// element, its nodes and the natural point if det J <= 0 at a Gauss point or a corner (for Q4
/// positive corners mean positive everywhere; for Q8 this catches badly placed mid-side nodes
/// at the points that matter).
PointShapes domain_points(const Mesh& mesh, int order);

/// Gauss-Legendre points along the given edges (`order` points each): position, length weight,
/// outward unit normal (the right of the edge's direction), the index of the edge in `edges`,
/// and the edge nodes' shape values (the traces of the element's shape functions: 1-D linear or
/// quadratic Lagrange), nodes sorted increasingly.
struct EdgePoints {
  std::vector<Vec2> x;
  std::vector<double> weight;
  std::vector<Vec2> normal;
  std::vector<int> edge;
  std::vector<int> offset{0};
  std::vector<int> node;
  std::vector<double> phi;
  int rows() const { return static_cast<int>(offset.size()) - 1; }
};
EdgePoints edge_points(const Mesh& mesh, const std::vector<BoundaryEdge>& edges, int order);

/// Physical position x(xi) of element e.
Vec2 map_to_physical(const Mesh& mesh, int element, const Vec2& xi);

/// Finds the element that holds a physical point and its natural coordinates. Candidates come
/// from cell lists of element centres, one per group of elements whose sizes lie within a factor
/// of 2 (so a graded mesh does not make every query scan the reach of its largest elements);
/// a candidate's box (for Q8 including its edges' bulge) is checked, then Newton's method on
/// the isoparametric map from the element's centre finds xi. Points within 1e-9 (natural
/// coordinates) of an element count as inside it, so points on edges are found. Keeps a
/// pointer to the mesh, which must outlive the locator and not change.
class PointLocator {
public:
  explicit PointLocator(const Mesh& mesh);
  /// False if no element holds x (element and xi are then unchanged).
  bool locate(const Vec2& x, int& element, Vec2& xi) const;

private:
  struct SizeGroup {
    double radius = 0.0; // largest half-diagonal of an element box in the group
    std::vector<int> element;
    neighbors::PointGrid grid;
  };
  const Mesh* mesh_;
  std::vector<BoundingBox> box_;
  std::vector<SizeGroup> groups_;
};

/// Shape values (and gradients if asked) at arbitrary physical points, one row per point.
/// Error naming the first point that no element holds; callers that sample lines crossing holes
/// filter their points with PointLocator::locate first.
PointShapes shapes_at(const Mesh& mesh, const PointLocator& locator,
                      const std::vector<Vec2>& points, bool gradients);

} // namespace mf::fem
