#pragma once
// Tetrahedra: the 4-node linear and 10-node quadratic isoparametric tetrahedron ([Zienkiewicz,
// Taylor & Zhu 2013], the chapter on shape functions: N = L_i for tet4; L_i (2 L_i - 1) at a
// corner and 4 L_i L_j at the middle of edge i-j for tet10, L the volume coordinates), their
// quadrature rules, meshes of them and the faces on a mesh's boundary.
//
// Reference tetrahedron: corners (0,0,0), (1,0,0), (0,1,0), (0,0,1), natural xi = (L1, L2, L3),
// L0 = 1 - L1 - L2 - L3. Local node order is gmsh's (types 4 and 11; the gmsh reference manual,
// "Node ordering", [Geuzaine & Remacle 2009]): the corners, then the middles of edges 0-1, 1-2,
// 2-0, 3-0, 3-2, 3-1.
#include "meshfree/core/types.hpp"
#include <string>
#include <vector>

namespace mf::fem {

constexpr int kTetMaxNodes = 10;

/// Shape functions N and natural derivatives dN/dxi at xi (4 or 10 entries; dN may be null).
void tet_shape_functions(bool quadratic, const Vec3& xi, double* N, Vec3* dN);

/// Natural coordinates of a tetrahedron's nodes in local order (4 or 10 of them).
const Vec3* tet_reference_nodes();
/// The two corners of the edge whose middle is local node 4 + k (k = 0..5).
const int* tet_edge_corners(int k);

/// Quadrature on the reference tetrahedron, exact for polynomials of degree `degree`; the
/// weights sum to its volume 1/6. Degree 1: the centroid; 2: the 4-point rule of [Keast 1986];
/// 3 to 5: the 14-point rule of degree 5 with positive weights [Walkington 2000] (the 5-point
/// degree-3 rule has a negative weight); above 5 a collapsed (Duffy) tensor Gauss rule.
struct TetRule {
  std::vector<Vec3> xi;
  std::vector<double> weight;
};
TetRule tet_rule(int degree);

/// The corners of local face f (0..3), ordered so that their normal by the right-hand rule
/// points out of a positively oriented tetrahedron; face f is opposite corner 3 - f.
const int* tet_face_corners(int f);
/// The natural point of local face f at the point (s, t) of the reference triangle (0,0),
/// (1,0), (0,1), which maps to the face's corners in order; `ds` and `dt` its derivatives.
Vec3 on_tet_face(int f, const Vec2& st, Vec3* ds = nullptr, Vec3* dt = nullptr);

struct TetMesh {
  bool quadratic = false;
  std::vector<Vec3> x;
  std::vector<int> connectivity; // 4 or 10 nodes per tetrahedron, gmsh's local order

  int nodes_per_element() const { return quadratic ? 10 : 4; }
  int element_count() const { return static_cast<int>(connectivity.size()) / nodes_per_element(); }
  int node_count() const { return static_cast<int>(x.size()); }
  const int* element(int e) const { return connectivity.data() + e * nodes_per_element(); }
};

/// det[x1 - x0, x2 - x0, x3 - x0] of element e's corners, six times its straight-sided volume:
/// positive for a positively oriented element (the reference tetrahedron's orientation).
double tet_corner_volume6(const TetMesh& mesh, int e);

/// Makes every element positively oriented (corners 1 and 2 swapped, with their edge nodes, in
/// negative ones). Error naming `what` and the element if one has no volume or names a
/// missing node.
void orient_tetrahedra(TetMesh& mesh, const std::string& what);

/// A face used by exactly one element: the element and its local face.
struct TetFace {
  int element = -1;
  int local_face = -1;
};
/// The boundary faces in element order. Error if a face is shared by more than two elements.
std::vector<TetFace> boundary_faces(const TetMesh& mesh);

/// Renumbers nodes in slabs of thickness `slab` along z, strips of that width along y within
/// each slab, then by x: contiguous node ranges are compact in space (small bandwidth, compact
/// MPI partitions), as the bricks' layers are.
void sort_nodes_for_locality(TetMesh& mesh, double slab);

/// Mean corner-to-corner edge length over the elements, the "h" of the mesh.
double characteristic_size(const TetMesh& mesh);

} // namespace mf::fem
