#include "meshfree/fem/mesh.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>

namespace mf::fem {

int nodes_per_element(ElementType type) {
  switch (type) {
  case ElementType::T3:
    return 3;
  case ElementType::Q4:
    return 4;
  case ElementType::Q8:
    return 8;
  }
  fail("fem: unknown element type ", static_cast<int>(type));
}

int corners_per_element(ElementType type) {
  return type == ElementType::T3 ? 3 : 4;
}

int gmsh_element_type(ElementType type) {
  return type == ElementType::T3 ? 2 : type == ElementType::Q4 ? 3 : 16;
}

const char* element_name(ElementType type) {
  switch (type) {
  case ElementType::T3:
    return "T3";
  case ElementType::Q4:
    return "Q4";
  case ElementType::Q8:
    return "Q8";
  }
  return "unknown";
}

namespace {

std::string node_list(const Mesh& mesh, int e) {
  std::ostringstream os;
  const int* n = mesh.element(e);
  for (int a = 0; a < mesh.nodes_per_element(); ++a) os << (a ? " " : "") << n[a];
  return os.str();
}

} // namespace

void check_mesh(const Mesh& mesh, const std::string& what) {
  const int npe = mesh.nodes_per_element();
  MF_REQUIRE(mesh.connectivity.size() % static_cast<std::size_t>(npe) == 0, what, ": ",
             mesh.connectivity.size(), " connectivity entries are not a whole number of ",
             element_name(mesh.type), " elements (", npe, " nodes each)");
  MF_REQUIRE(mesh.element_count() > 0, what, ": the mesh has no elements");
  for (int e = 0; e < mesh.element_count(); ++e)
    for (int a = 0; a < npe; ++a) {
      const int n = mesh.element(e)[a];
      MF_REQUIRE(n >= 0 && n < mesh.node_count(), what, ": element ", e, " names node ", n,
                 " but the mesh has nodes 0..", mesh.node_count() - 1);
    }
}

double signed_area(const Mesh& mesh, int element) {
  const int nc = corners_per_element(mesh.type);
  const int* n = mesh.element(element);
  // Boundary nodes in turn: corners, with the mid-side node of each edge between them (Q8).
  std::array<int, 8> ring{};
  int m = 0;
  for (int k = 0; k < nc; ++k) {
    ring[m++] = n[k];
    if (mesh.type == ElementType::Q8) ring[m++] = n[nc + k];
  }
  double a = 0.0; // shoelace formula
  for (int k = 0; k < m; ++k) {
    const Vec2& p = mesh.x[ring[k]];
    const Vec2& q = mesh.x[ring[(k + 1) % m]];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

int orient_counter_clockwise(Mesh& mesh, const std::string& what) {
  check_mesh(mesh, what);
  const int npe = mesh.nodes_per_element();
  const int nc = corners_per_element(mesh.type);
  int reversed = 0;
  for (int e = 0; e < mesh.element_count(); ++e) {
    int* n = mesh.connectivity.data() + e * npe;
    double scale = 0.0; // squared longest edge: what "no area" is measured against
    for (int k = 0; k < nc; ++k)
      scale = std::max(scale, (mesh.x[n[(k + 1) % nc]] - mesh.x[n[k]]).squaredNorm());
    const double a = signed_area(mesh, e);
    MF_REQUIRE(std::abs(a) > 1e-12 * scale, what, ": element ", e, " (nodes ", node_list(mesh, e),
               ") has no area (", a, "); it is degenerate");
    if (a > 0.0) continue;
    // Reverse the corner cycle keeping corner 0; a Q8 mid-side node follows its edge:
    // new edge k runs between old corners (nc - k) % nc and nc - 1 - k, old edge nc - 1 - k.
    std::array<int, 8> old{};
    std::copy(n, n + npe, old.begin());
    for (int k = 0; k < nc; ++k) n[k] = old[(nc - k) % nc];
    if (mesh.type == ElementType::Q8)
      for (int k = 0; k < nc; ++k) n[nc + k] = old[nc + nc - 1 - k];
    ++reversed;
  }
  return reversed;
}

Mesh structured_rectangle(const Vec2& origin, const Vec2& size, int nx, int ny, ElementType type) {
  MF_REQUIRE(nx >= 1 && ny >= 1, "structured_rectangle: need at least one cell each way, got ", nx,
             " x ", ny);
  MF_REQUIRE(size.x() > 0.0 && size.y() > 0.0,
             "structured_rectangle: the size must be positive, got (", size.x(), ", ", size.y(),
             ")");
  Mesh mesh;
  mesh.type = type;
  // A lattice with `s` steps per cell (s = 2 for Q8: corners and mid-side nodes); Q8 has no
  // node at the lattice points in the middle of a cell.
  const int s = type == ElementType::Q8 ? 2 : 1;
  const int li = s * nx + 1, lj = s * ny + 1;
  std::vector<int> id(static_cast<std::size_t>(li) * lj, -1);
  for (int j = 0; j < lj; ++j)
    for (int i = 0; i < li; ++i) {
      if (s == 2 && i % 2 == 1 && j % 2 == 1) continue;
      id[j * li + i] = mesh.node_count();
      // Both ends exact, so that the outline is exactly the rectangle.
      const double fx = static_cast<double>(i) / (li - 1), fy = static_cast<double>(j) / (lj - 1);
      mesh.x.emplace_back(i == li - 1 ? origin.x() + size.x() : origin.x() + fx * size.x(),
                          j == lj - 1 ? origin.y() + size.y() : origin.y() + fy * size.y());
    }
  auto at = [&](int i, int j) { return id[j * li + i]; };
  for (int cj = 0; cj < ny; ++cj)
    for (int ci = 0; ci < nx; ++ci) {
      const int i = s * ci, j = s * cj;
      const int a = at(i, j), b = at(i + s, j), c = at(i + s, j + s), d = at(i, j + s);
      switch (type) {
      case ElementType::T3:
        mesh.connectivity.insert(mesh.connectivity.end(), {a, b, c, a, c, d});
        break;
      case ElementType::Q4:
        mesh.connectivity.insert(mesh.connectivity.end(), {a, b, c, d});
        break;
      case ElementType::Q8:
        mesh.connectivity.insert(
            mesh.connectivity.end(),
            {a, b, c, d, at(i + 1, j), at(i + 2, j + 1), at(i + 1, j + 2), at(i, j + 1)});
        break;
      }
    }
  return mesh;
}

void renumber_nodes(Mesh& mesh, const std::vector<int>& new_of_old) {
  const int n = mesh.node_count();
  MF_REQUIRE(static_cast<int>(new_of_old.size()) == n, "renumber_nodes: ", new_of_old.size(),
             " new numbers for ", n, " nodes");
  std::vector<Vec2> x(mesh.x.size());
  std::vector<char> seen(mesh.x.size(), 0);
  for (int i = 0; i < n; ++i) {
    const int k = new_of_old[i];
    MF_REQUIRE(k >= 0 && k < n && !seen[k],
               "renumber_nodes: the new numbers are not a "
               "permutation of 0..",
               n - 1, " (node ", i, " -> ", k, ")");
    seen[k] = 1;
    x[k] = mesh.x[i];
  }
  mesh.x = std::move(x);
  for (int& c : mesh.connectivity) c = new_of_old[c];
}

void sort_nodes_for_locality(Mesh& mesh, double strip) {
  MF_REQUIRE(strip > 0.0, "sort_nodes_for_locality: the strip height must be positive, got ",
             strip);
  const int n = mesh.node_count();
  if (n == 0) return;
  double ylo = mesh.x[0].y();
  for (const Vec2& p : mesh.x) ylo = std::min(ylo, p.y());
  // Same key as geometry::generate_nodes: strips centred on ylo + k * strip, then x, then y.
  std::vector<double> row(n);
  for (int i = 0; i < n; ++i) row[i] = std::floor((mesh.x[i].y() - ylo) / strip + 0.5);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (row[a] != row[b]) return row[a] < row[b];
    if (mesh.x[a].x() != mesh.x[b].x()) return mesh.x[a].x() < mesh.x[b].x();
    return mesh.x[a].y() < mesh.x[b].y();
  });
  std::vector<int> new_of_old(n);
  for (int k = 0; k < n; ++k) new_of_old[order[k]] = k;
  renumber_nodes(mesh, new_of_old);
}

double characteristic_size(const Mesh& mesh) {
  MF_REQUIRE(mesh.element_count() > 0, "characteristic_size: the mesh has no elements");
  const int nc = corners_per_element(mesh.type);
  double sum = 0.0;
  for (int e = 0; e < mesh.element_count(); ++e) {
    const int* n = mesh.element(e);
    for (int k = 0; k < nc; ++k) sum += (mesh.x[n[(k + 1) % nc]] - mesh.x[n[k]]).norm();
  }
  return sum / (static_cast<double>(nc) * mesh.element_count());
}

std::vector<BoundaryEdge> boundary_edges(const Mesh& mesh) {
  const int nc = corners_per_element(mesh.type);
  struct Side {
    int lo, hi, element, local;
  };
  std::vector<Side> sides;
  sides.reserve(static_cast<std::size_t>(mesh.element_count()) * nc);
  for (int e = 0; e < mesh.element_count(); ++e) {
    const int* n = mesh.element(e);
    for (int k = 0; k < nc; ++k) {
      const int a = n[k], b = n[(k + 1) % nc];
      sides.push_back({std::min(a, b), std::max(a, b), e, k});
    }
  }
  // Equal corner pairs become neighbours; ties keep element order, so the result is too.
  std::stable_sort(sides.begin(), sides.end(), [](const Side& p, const Side& q) {
    return p.lo != q.lo ? p.lo < q.lo : p.hi < q.hi;
  });
  std::vector<std::array<int, 2>> found; // (element, local edge) of boundary edges
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) ++j;
    MF_REQUIRE(j - i <= 2, "boundary_edges: the edge between nodes ", sides[i].lo, " and ",
               sides[i].hi, " belongs to ", j - i,
               " elements (at most 2 in a plane mesh), among them ", sides[i].element, " and ",
               sides[i + 1].element);
    if (j - i == 1) {
      found.push_back({sides[i].element, sides[i].local});
    } else {
      // Two counter-clockwise neighbours run along their common edge in opposite directions.
      const Side &p = sides[i], &q = sides[i + 1];
      const int pa = mesh.element(p.element)[p.local];
      const int qa = mesh.element(q.element)[q.local];
      MF_REQUIRE(pa != qa, "boundary_edges: elements ", p.element, " and ", q.element,
                 " run along their common edge (nodes ", p.lo, ", ", p.hi,
                 ") in the same direction; they overlap or one is inverted");
    }
    i = j;
  }
  std::sort(found.begin(), found.end());
  std::vector<BoundaryEdge> edges;
  edges.reserve(found.size());
  for (const auto& [e, k] : found) {
    const int* n = mesh.element(e);
    BoundaryEdge b;
    b.element = e;
    b.local_edge = k;
    b.nodes[0] = n[k];
    b.nodes[1] = n[(k + 1) % nc];
    b.count = 2;
    if (mesh.type == ElementType::Q8) {
      b.nodes[2] = n[nc + k];
      b.count = 3;
    }
    edges.push_back(b);
  }
  return edges;
}

} // namespace mf::fem
