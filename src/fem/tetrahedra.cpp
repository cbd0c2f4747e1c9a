#include "meshfree/fem/tetrahedra.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace mf::fem {

namespace {

/// The corners of the edge whose middle is local node 4 + k (gmsh's order).
constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};

constexpr int kFace[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

/// Adds the orbit of barycentric points (a, a, a, 1 - 3a) (4 points) with weight w each.
void add_orbit4(TetRule& r, double a, double w) {
  const double b = 1.0 - 3.0 * a;
  for (const Vec3& p : {Vec3(a, a, a), Vec3(b, a, a), Vec3(a, b, a), Vec3(a, a, b)}) {
    r.xi.push_back(p);
    r.weight.push_back(w);
  }
}

/// Adds the orbit of barycentric points (a, a, 1/2 - a, 1/2 - a) (6 points) with weight w each.
void add_orbit6(TetRule& r, double a, double w) {
  const double b = 0.5 - a;
  for (const Vec3& p :
       {Vec3(a, b, b), Vec3(b, a, b), Vec3(b, b, a), Vec3(b, a, a), Vec3(a, b, a), Vec3(a, a, b)}) {
    r.xi.push_back(p);
    r.weight.push_back(w);
  }
}

/// Collapsed (Duffy) rule: x = u, y = (1 - u) v, z = (1 - u)(1 - v) w over the unit cube,
/// Jacobian (1 - u)^2 (1 - v). A polynomial of degree d becomes degree d + 2 in u, d + 1 in v
/// and d in w, so n = ceil((d + 3) / 2) Gauss points per direction integrate it exactly.
TetRule collapsed_rule(int degree) {
  const int n = (degree + 4) / 2;
  MF_REQUIRE(n <= 20, "tetrahedron quadrature: degree ", degree, " is above the highest (37)");
  const GaussRule& g = gauss_legendre(n);
  TetRule r;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double u = 0.5 * (1.0 + g.points[i]), v = 0.5 * (1.0 + g.points[j]),
                     w = 0.5 * (1.0 + g.points[k]);
        r.xi.emplace_back(u, (1.0 - u) * v, (1.0 - u) * (1.0 - v) * w);
        r.weight.push_back(0.125 * g.weights[i] * g.weights[j] * g.weights[k] * (1.0 - u) *
                           (1.0 - u) * (1.0 - v));
      }
  return r;
}

} // namespace

void tet_shape_functions(bool quadratic, const Vec3& xi, double* N, Vec3* dN) {
  const double L[4] = {1.0 - xi.x() - xi.y() - xi.z(), xi.x(), xi.y(), xi.z()};
  static const Vec3 dL[4] = {{-1.0, -1.0, -1.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  if (!quadratic) {
    for (int a = 0; a < 4; ++a) {
      N[a] = L[a];
      if (dN) dN[a] = dL[a];
    }
    return;
  }
  for (int a = 0; a < 4; ++a) {
    N[a] = L[a] * (2.0 * L[a] - 1.0);
    if (dN) dN[a] = (4.0 * L[a] - 1.0) * dL[a];
  }
  for (int k = 0; k < 6; ++k) {
    const int i = kEdge[k][0], j = kEdge[k][1];
    N[4 + k] = 4.0 * L[i] * L[j];
    if (dN) dN[4 + k] = 4.0 * (L[i] * dL[j] + L[j] * dL[i]);
  }
}

const Vec3* tet_reference_nodes() {
  static const std::array<Vec3, 10> nodes = [] {
    std::array<Vec3, 10> n{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    for (int k = 0; k < 6; ++k) n[4 + k] = 0.5 * (n[kEdge[k][0]] + n[kEdge[k][1]]);
    return n;
  }();
  return nodes.data();
}

TetRule tet_rule(int degree) {
  MF_REQUIRE(degree >= 1, "tetrahedron quadrature: the degree must be at least 1, got ", degree);
  TetRule r;
  if (degree == 1) {
    r.xi.emplace_back(0.25, 0.25, 0.25);
    r.weight.push_back(1.0 / 6.0);
  } else if (degree == 2) {
    add_orbit4(r, (5.0 - std::sqrt(5.0)) / 20.0, 1.0 / 24.0);
  } else if (degree <= 5) {
    add_orbit4(r, 0.3108859192633006, 0.01878132095300264);
    add_orbit4(r, 0.09273525031089123, 0.01224884051939366);
    add_orbit6(r, 0.04550370412564965, 0.007091003462846911);
  } else {
    r = collapsed_rule(degree);
  }
  return r;
}

const int* tet_face_corners(int f) {
  return kFace[f];
}

const int* tet_edge_corners(int k) {
  return kEdge[k];
}

Vec3 on_tet_face(int f, const Vec2& st, Vec3* ds, Vec3* dt) {
  const Vec3* ref = tet_reference_nodes();
  const Vec3 &a = ref[kFace[f][0]], &b = ref[kFace[f][1]], &c = ref[kFace[f][2]];
  if (ds) *ds = b - a;
  if (dt) *dt = c - a;
  return a + st.x() * (b - a) + st.y() * (c - a);
}

double tet_corner_volume6(const TetMesh& mesh, int e) {
  const int* n = mesh.element(e);
  Mat3 m;
  for (int a = 0; a < 3; ++a) m.col(a) = mesh.x[n[a + 1]] - mesh.x[n[0]];
  return m.determinant();
}

void orient_tetrahedra(TetMesh& mesh, const std::string& what) {
  const int npe = mesh.nodes_per_element();
  MF_REQUIRE(mesh.connectivity.size() % npe == 0, what, ": ", mesh.connectivity.size(),
             " node numbers are not a whole number of ", npe, "-node tetrahedra");
  for (int c : mesh.connectivity)
    MF_REQUIRE(c >= 0 && c < mesh.node_count(), what, ": an element names node ", c, " of ",
               mesh.node_count());
  // Corners 1 and 2 swapped: edge 0-1 becomes 0-2, 3-1 becomes 3-2, 1-2 stays.
  static constexpr int kSwap[10] = {0, 2, 1, 3, 6, 5, 4, 7, 9, 8};
  for (int e = 0; e < mesh.element_count(); ++e) {
    const double v = tet_corner_volume6(mesh, e);
    const int* n = mesh.element(e);
    double size = 0.0;
    for (int a = 1; a < 4; ++a) size = std::max(size, (mesh.x[n[a]] - mesh.x[n[0]]).norm());
    MF_REQUIRE(std::abs(v) > 1e-12 * size * size * size, what, ": tetrahedron ", e,
               " has no volume");
    if (v > 0.0) continue;
    int* m = mesh.connectivity.data() + e * npe;
    int old[10];
    std::copy(m, m + npe, old);
    for (int a = 0; a < npe; ++a) m[a] = old[kSwap[a]];
  }
}

std::vector<TetFace> boundary_faces(const TetMesh& mesh) {
  // Every element's faces by their sorted corners; a face listed once lies on the boundary.
  struct Entry {
    std::array<int, 3> corners;
    TetFace face;
  };
  std::vector<Entry> all;
  all.reserve(4 * static_cast<std::size_t>(mesh.element_count()));
  for (int e = 0; e < mesh.element_count(); ++e)
    for (int f = 0; f < 4; ++f) {
      Entry en{{}, {e, f}};
      for (int k = 0; k < 3; ++k) en.corners[k] = mesh.element(e)[kFace[f][k]];
      std::sort(en.corners.begin(), en.corners.end());
      all.push_back(en);
    }
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.face.element < b.face.element;
  });
  std::vector<TetFace> out;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j].corners == all[i].corners) ++j;
    MF_REQUIRE(j - i <= 2, "tetrahedra: a face of element ", all[i].face.element,
               " is shared by more than two elements");
    if (j - i == 1) out.push_back(all[i].face);
    i = j;
  }
  std::sort(out.begin(), out.end(), [](const TetFace& a, const TetFace& b) {
    return a.element != b.element ? a.element < b.element : a.local_face < b.local_face;
  });
  return out;
}

void sort_nodes_for_locality(TetMesh& mesh, double slab) {
  MF_REQUIRE(slab > 0.0, "sort_nodes_for_locality: the slab thickness must be positive, got ",
             slab);
  const int n = mesh.node_count();
  if (n == 0) return;
  Vec3 lo = mesh.x[0];
  for (const Vec3& p : mesh.x) lo = lo.cwiseMin(p);
  std::vector<std::array<double, 3>> key(n);
  for (int i = 0; i < n; ++i)
    key[i] = {std::floor((mesh.x[i].z() - lo.z()) / slab + 0.5),
              std::floor((mesh.x[i].y() - lo.y()) / slab + 0.5), mesh.x[i].x()};
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::vector<int> new_of_old(n);
  std::vector<Vec3> x(n);
  for (int k = 0; k < n; ++k) new_of_old[order[k]] = k, x[k] = mesh.x[order[k]];
  mesh.x = std::move(x);
  for (int& c : mesh.connectivity) c = new_of_old[c];
}

double characteristic_size(const TetMesh& mesh) {
  MF_REQUIRE(mesh.element_count() > 0, "characteristic_size: the mesh has no elements");
  double sum = 0.0;
  for (int e = 0; e < mesh.element_count(); ++e) {
    const int* n = mesh.element(e);
    for (const auto& edge : kEdge) sum += (mesh.x[n[edge[0]]] - mesh.x[n[edge[1]]]).norm();
  }
  return sum / (6.0 * mesh.element_count());
}

} // namespace mf::fem
