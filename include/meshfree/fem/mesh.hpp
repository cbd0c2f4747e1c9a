#pragma once
// Finite-element meshes of a plane body: one element type per mesh (linear triangles, bilinear
// quadrilaterals or 8-node serendipity quadrilaterals), read from gmsh or built on a rectangle,
// and the mesh topology the boundary conditions need (the edges on the body's outline).
#include "meshfree/core/types.hpp"
#include <string>
#include <vector>

namespace mf::fem {

enum class ElementType { T3, Q4, Q8 }; // linear triangle, bilinear quad, 8-node serendipity quad

int nodes_per_element(ElementType type);
/// Corner nodes (3 or 4) = edges per element.
int corners_per_element(ElementType type);
const char* element_name(ElementType type); // "T3", "Q4", "Q8"
/// gmsh's number of the element type: 2 (T3), 3 (Q4), 16 (Q8), the same local node order.
int gmsh_element_type(ElementType type);

/// Local node order: corners counter-clockwise, then mid-side nodes (Q8: local 4 on edge 0-1,
/// 5 on 1-2, 6 on 2-3, 7 on 3-0), the gmsh convention. Local edge k runs from corner k to
/// corner (k + 1) % corners; its mid-side node (Q8) is local node corners + k.
struct Mesh {
  ElementType type = ElementType::Q4;
  std::vector<Vec2> x;
  std::vector<int> connectivity; // nodes_per_element(type) entries per element

  int nodes_per_element() const { return fem::nodes_per_element(type); }
  int element_count() const {
    return static_cast<int>(connectivity.size()) / fem::nodes_per_element(type);
  }
  int node_count() const { return static_cast<int>(x.size()); }
  /// The nodes of element e (nodes_per_element() of them).
  const int* element(int e) const { return connectivity.data() + e * nodes_per_element(); }
};

/// Checks that the connectivity is a whole number of elements naming existing nodes; `what`
/// names the mesh in the message (a file, "structured_rectangle", ...).
void check_mesh(const Mesh& mesh, const std::string& what);

/// Signed area of the polygon through the element's boundary nodes (Q8: corners and mid-side
/// nodes in turn); positive for a counter-clockwise element. For a curved Q8 this is not the
/// element's exact area (domain_points gives that), but its sign is the orientation.
double signed_area(const Mesh& mesh, int element);

/// Makes every element counter-clockwise by reversing the node order of clockwise ones (T3:
/// 0 2 1; Q4: 0 3 2 1; Q8: 0 3 2 1 7 6 5 4, so each mid-side node stays on its edge). Returns
/// how many elements were reversed. Error naming `what`, the element and its nodes if an
/// element has no area.
int orient_counter_clockwise(Mesh& mesh, const std::string& what);

/// Gmsh MSH 2.2 and 4.1 ASCII files. Keeps the 2-D elements (gmsh types 2 = T3, 3 = Q4,
/// 16 = Q8); ignores points and lines. Error naming the file and the problem if the file cannot
/// be read, is binary or another version, is cut short, has no 2-D elements or mixes two 2-D
/// types, has another 2-D type (6-node triangles, 9-node quads, ...) or 3-D elements, if an
/// element names a missing node, or if the nodes do not lie in one plane z = const. Drops nodes
/// that no element uses, numbers the rest 0..n-1 in file order, and makes every element
/// counter-clockwise.
Mesh read_gmsh(const std::string& path);

/// Structured mesh of the rectangle [origin, origin + size]: nx x ny cells; T3 splits each cell
/// into two triangles along the diagonal from its lower-left to its upper-right corner. Nodes
/// are numbered row by row (y, then x), which is already local.
Mesh structured_rectangle(const Vec2& origin, const Vec2& size, int nx, int ny, ElementType type);

/// Renumbers nodes: node i becomes new_of_old[i] (a permutation of 0..n-1).
void renumber_nodes(Mesh& mesh, const std::vector<int>& new_of_old);

/// Renumbers nodes in horizontal strips of height `strip` (by strip, then x, then y), so that
/// contiguous node ranges are compact in space (small bandwidth, compact MPI partitions): the
/// ordering geometry::generate_nodes gives meshfree nodes. A strip of about the element size
/// (characteristic_size) keeps the bandwidth near the number of nodes in two strips.
void sort_nodes_for_locality(Mesh& mesh, double strip);

/// Mean length of the element edges measured corner to corner (each element's edges counted
/// once per element), the "h" of the mesh.
double characteristic_size(const Mesh& mesh);

/// An edge used by exactly one element: the element, its local edge, and the edge's 2 (T3/Q4)
/// or 3 (Q8: ends, then mid) nodes, ordered so that the body lies to the left of the way from
/// nodes[0] to nodes[1] (the outline runs counter-clockwise, holes clockwise).
struct BoundaryEdge {
  int element = -1;
  int local_edge = -1;
  int nodes[3] = {-1, -1, -1};
  int count = 0; // 2 or 3
};

/// The boundary edges in element order. Error if an edge is shared by more than two elements or
/// by two elements that run along it in the same direction (overlapping or inverted elements).
std::vector<BoundaryEdge> boundary_edges(const Mesh& mesh);

} // namespace mf::fem
