#include "meshfree/fem/elements.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include <algorithm>
#include <cmath>
#include <sstream>

namespace mf::fem {

namespace {

const Vec2 kT3Nodes[3] = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
const Vec2 kQ8Nodes[8] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0},
                          {0.0, -1.0},  {1.0, 0.0},  {0.0, 1.0}, {-1.0, 0.0}};

} // namespace

const Vec2* reference_nodes(ElementType type) {
  return type == ElementType::T3 ? kT3Nodes : kQ8Nodes; // Q4: the first four of Q8's
}

void shape_functions(ElementType type, const Vec2& xi, double* N, Vec2* dN) {
  const double s = xi.x(), t = xi.y();
  switch (type) {
  case ElementType::T3:
    N[0] = 1.0 - s - t, N[1] = s, N[2] = t;
    if (dN) dN[0] = {-1.0, -1.0}, dN[1] = {1.0, 0.0}, dN[2] = {0.0, 1.0};
    return;
  case ElementType::Q4:
    for (int a = 0; a < 4; ++a) {
      const double sa = kQ8Nodes[a].x(), ta = kQ8Nodes[a].y();
      N[a] = 0.25 * (1.0 + s * sa) * (1.0 + t * ta);
      if (dN) dN[a] = {0.25 * sa * (1.0 + t * ta), 0.25 * ta * (1.0 + s * sa)};
    }
    return;
  case ElementType::Q8:
    // Serendipity functions (Zienkiewicz & Taylor vol. 1, sec. 6.4.1): corners
    // N = (1 + s sa)(1 + t ta)(s sa + t ta - 1) / 4, mid-side nodes (1 - s^2)(1 + t ta) / 2 on
    // sa = 0 and (1 + s sa)(1 - t^2) / 2 on ta = 0.
    for (int a = 0; a < 4; ++a) {
      const double sa = kQ8Nodes[a].x(), ta = kQ8Nodes[a].y();
      const double ps = 1.0 + s * sa, pt = 1.0 + t * ta;
      N[a] = 0.25 * ps * pt * (s * sa + t * ta - 1.0);
      if (dN)
        dN[a] = {0.25 * sa * pt * (2.0 * s * sa + t * ta),
                 0.25 * ta * ps * (s * sa + 2.0 * t * ta)};
    }
    for (int a = 4; a < 8; a += 2) { // on t = -1, t = 1
      const double ta = kQ8Nodes[a].y();
      N[a] = 0.5 * (1.0 - s * s) * (1.0 + t * ta);
      if (dN) dN[a] = {-s * (1.0 + t * ta), 0.5 * (1.0 - s * s) * ta};
    }
    for (int a = 5; a < 8; a += 2) { // on s = 1, s = -1
      const double sa = kQ8Nodes[a].x();
      N[a] = 0.5 * (1.0 + s * sa) * (1.0 - t * t);
      if (dN) dN[a] = {0.5 * sa * (1.0 - t * t), -t * (1.0 + s * sa)};
    }
    return;
  }
}

namespace {

/// Adds the three points (a, a), (1 - 2a, a), (a, 1 - 2a) of a symmetric triangle rule, with
/// `w` the weight as a fraction of the triangle's area (the reference triangle's area is 1/2).
void add_orbit(ReferenceRule& r, double a, double w) {
  for (const Vec2& p : {Vec2(a, a), Vec2(1.0 - 2.0 * a, a), Vec2(a, 1.0 - 2.0 * a)}) {
    r.xi.push_back(p);
    r.weight.push_back(0.5 * w);
  }
}

ReferenceRule triangle_rule(int degree) {
  ReferenceRule r;
  if (degree <= 1) { // centroid
    r.xi.push_back({1.0 / 3.0, 1.0 / 3.0});
    r.weight.push_back(0.5);
  } else if (degree == 2) { // Strang & Fix (1973), table 4.1: three interior points
    add_orbit(r, 1.0 / 6.0, 1.0 / 3.0);
  } else if (degree <= 4) {
    // Dunavant (1985), degree 4, 6 points, positive weights (his degree-3 rule has a negative
    // weight, so degree 3 uses this one too). The second weight is 1/3 - w1 so that the weights
    // sum to the area to the last bit.
    const double w1 = 0.223381589678011465944;
    add_orbit(r, 0.445948490915964886318, w1);
    add_orbit(r, 0.091576213509770743460, 1.0 / 3.0 - w1);
  } else if (degree == 5) {
    // Radon's 7-point rule (Strang & Fix table 4.1; Dunavant 1985 degree 5) in closed form.
    const double q = std::sqrt(15.0);
    r.xi.push_back({1.0 / 3.0, 1.0 / 3.0});
    r.weight.push_back(0.5 * 9.0 / 40.0);
    add_orbit(r, (6.0 - q) / 21.0, (155.0 - q) / 1200.0);
    add_orbit(r, (6.0 + q) / 21.0, (155.0 + q) / 1200.0);
  } else {
    // Collapsed (Duffy) rule: x = u, y = (1 - u) v over the unit square, Jacobian (1 - u). A
    // polynomial of degree d becomes degree d + 1 in u and d in v, so n = ceil((d + 2) / 2)
    // Gauss points per direction integrate it exactly.
    const int n = (degree + 3) / 2;
    MF_REQUIRE(n <= 20, "triangle quadrature: degree ", degree, " is above the highest (38)");
    const GaussRule& g = gauss_legendre(n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double u = 0.5 * (1.0 + g.points[i]), v = 0.5 * (1.0 + g.points[j]);
        r.xi.push_back({u, (1.0 - u) * v});
        r.weight.push_back(0.25 * g.weights[i] * g.weights[j] * (1.0 - u));
      }
  }
  return r;
}

} // namespace

ReferenceRule domain_rule(ElementType type, int order) {
  MF_REQUIRE(order >= 1, element_name(type), " quadrature: the order must be at least 1, got ",
             order);
  if (type == ElementType::T3) return triangle_rule(order);
  MF_REQUIRE(order <= 20, element_name(type),
             " quadrature: at most 20 Gauss points per direction, got ", order);
  const GaussRule& g = gauss_legendre(order);
  ReferenceRule r;
  for (int j = 0; j < order; ++j)
    for (int i = 0; i < order; ++i) {
      r.xi.push_back({g.points[i], g.points[j]});
      r.weight.push_back(g.weights[i] * g.weights[j]);
    }
  return r;
}

int default_order(ElementType type) {
  switch (type) {
  case ElementType::T3:
    return 1;
  case ElementType::Q4:
    return 2;
  case ElementType::Q8:
    return 3;
  }
  return 2;
}

int default_edge_order(ElementType type) {
  return type == ElementType::Q8 ? 3 : 2;
}

namespace {

/// The nodes of one element and their coordinates, gathered once per element.
struct ElementNodes {
  int count = 0;
  int node[kMaxElementNodes];
  Vec2 x[kMaxElementNodes];
  void gather(const Mesh& mesh, int e) {
    count = mesh.nodes_per_element();
    const int* n = mesh.element(e);
    for (int a = 0; a < count; ++a) node[a] = n[a], x[a] = mesh.x[n[a]];
  }
};

/// Jacobian J(i, j) = d x_i / d xi_j = sum_a x_a,i dN_a/dxi_j.
Mat2 jacobian(const ElementNodes& en, const Vec2* dN) {
  Mat2 J = Mat2::Zero();
  for (int a = 0; a < en.count; ++a) J += en.x[a] * dN[a].transpose();
  return J;
}

/// Local indices ordered by global node number (insertion sort: at most 8 entries).
void sorted_order(const ElementNodes& en, int* perm) {
  for (int a = 0; a < en.count; ++a) {
    int b = a;
    while (b > 0 && en.node[perm[b - 1]] > en.node[a]) perm[b] = perm[b - 1], --b;
    perm[b] = a;
  }
}

std::string describe(const Mesh& mesh, int e) {
  std::ostringstream os;
  os << element_name(mesh.type) << " element " << e << " (nodes";
  const int* n = mesh.element(e);
  for (int a = 0; a < mesh.nodes_per_element(); ++a) os << " " << n[a];
  os << ")";
  return os.str();
}

[[noreturn]] void bad_jacobian(const Mesh& mesh, int e, const Vec2& xi, double det) {
  fail("fem: ", describe(mesh, e), " has det J = ", det, " <= 0 at natural point (", xi.x(), ", ",
       xi.y(), "); it is inverted or too distorted (check its node order and mid-side nodes)");
}

/// Appends one row: the element's nodes sorted, with phi (and dphi if dN_dx is given).
void append_row(const ElementNodes& en, const double* N, const Vec2* dN_dx, std::vector<int>& node,
                std::vector<double>& phi, std::vector<Vec2>* dphi, std::vector<int>& offset) {
  int perm[kMaxElementNodes];
  sorted_order(en, perm);
  for (int k = 0; k < en.count; ++k) {
    const int a = perm[k];
    node.push_back(en.node[a]);
    phi.push_back(N[a]);
    if (dphi) dphi->push_back(dN_dx[a]);
  }
  offset.push_back(static_cast<int>(node.size()));
}

} // namespace

PointShapes domain_points(const Mesh& mesh, int order) {
  check_mesh(mesh, "domain_points");
  const ReferenceRule rule = domain_rule(mesh.type, order);
  const int nq = static_cast<int>(rule.xi.size());
  const int npe = mesh.nodes_per_element();
  const int ne = mesh.element_count();
  // Reference values are the same in every element.
  std::vector<double> N(static_cast<std::size_t>(nq) * npe);
  std::vector<Vec2> dN(static_cast<std::size_t>(nq) * npe);
  for (int q = 0; q < nq; ++q) shape_functions(mesh.type, rule.xi[q], &N[q * npe], &dN[q * npe]);
  // Corner checks: for Q4, det J is linear in each natural coordinate, so positive corners
  // mean a valid element; for Q8 they catch most misplaced mid-side nodes.
  const int nc = mesh.type == ElementType::T3 ? 0 : 4;
  double Nc[kMaxElementNodes];
  Vec2 dNc[4][kMaxElementNodes];
  for (int c = 0; c < nc; ++c)
    shape_functions(mesh.type, reference_nodes(mesh.type)[c], Nc, dNc[c]);

  PointShapes out;
  const std::size_t rows = static_cast<std::size_t>(ne) * nq;
  out.x.reserve(rows);
  out.weight.reserve(rows);
  out.element.reserve(rows);
  out.offset.reserve(rows + 1);
  out.node.reserve(rows * npe);
  out.phi.reserve(rows * npe);
  out.dphi.reserve(rows * npe);
  ElementNodes en;
  Vec2 dN_dx[kMaxElementNodes];
  for (int e = 0; e < ne; ++e) {
    en.gather(mesh, e);
    for (int c = 0; c < nc; ++c) {
      const double det = jacobian(en, dNc[c]).determinant();
      if (!(det > 0.0)) bad_jacobian(mesh, e, reference_nodes(mesh.type)[c], det);
    }
    for (int q = 0; q < nq; ++q) {
      const double* Nq = &N[q * npe];
      const Vec2* dNq = &dN[q * npe];
      const Mat2 J = jacobian(en, dNq);
      const double det = J.determinant();
      if (!(det > 0.0)) bad_jacobian(mesh, e, rule.xi[q], det);
      const Mat2 JinvT = J.inverse().transpose(); // dN/dx = J^{-T} dN/dxi
      Vec2 x = Vec2::Zero();
      for (int a = 0; a < npe; ++a) {
        x += Nq[a] * en.x[a];
        dN_dx[a] = JinvT * dNq[a];
      }
      out.x.push_back(x);
      out.weight.push_back(rule.weight[q] * det);
      out.element.push_back(e);
      append_row(en, Nq, dN_dx, out.node, out.phi, &out.dphi, out.offset);
    }
  }
  return out;
}

EdgePoints edge_points(const Mesh& mesh, const std::vector<BoundaryEdge>& edges, int order) {
  MF_REQUIRE(order >= 1 && order <= 20, "edge_points: the order must be in 1..20, got ", order);
  const int count = mesh.type == ElementType::Q8 ? 3 : 2;
  const GaussRule& g = gauss_legendre(order);
  EdgePoints out;
  const std::size_t rows = edges.size() * order;
  out.x.reserve(rows);
  out.weight.reserve(rows);
  out.normal.reserve(rows);
  out.edge.reserve(rows);
  out.offset.reserve(rows + 1);
  out.node.reserve(rows * count);
  out.phi.reserve(rows * count);
  ElementNodes en;
  en.count = count;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const BoundaryEdge& b = edges[k];
    MF_REQUIRE(b.count == count, "edge_points: edge ", k, " has ", b.count, " nodes, a ",
               element_name(mesh.type), " edge has ", count);
    for (int a = 0; a < count; ++a) {
      MF_REQUIRE(b.nodes[a] >= 0 && b.nodes[a] < mesh.node_count(), "edge_points: edge ", k,
                 " names node ", b.nodes[a], " but the mesh has nodes 0..", mesh.node_count() - 1);
      en.node[a] = b.nodes[a];
      en.x[a] = mesh.x[b.nodes[a]];
    }
    for (int q = 0; q < order; ++q) {
      // Traces of the element's shape functions on the edge, s in [-1, 1] from nodes[0] to
      // nodes[1]: linear, or quadratic Lagrange with the mid-side node at s = 0.
      const double s = g.points[q];
      double N[3];
      double dN[3];
      if (count == 2) {
        N[0] = 0.5 * (1.0 - s), N[1] = 0.5 * (1.0 + s);
        dN[0] = -0.5, dN[1] = 0.5;
      } else {
        N[0] = 0.5 * s * (s - 1.0), N[1] = 0.5 * s * (s + 1.0), N[2] = 1.0 - s * s;
        dN[0] = s - 0.5, dN[1] = s + 0.5, dN[2] = -2.0 * s;
      }
      Vec2 x = Vec2::Zero(), t = Vec2::Zero();
      for (int a = 0; a < count; ++a) x += N[a] * en.x[a], t += dN[a] * en.x[a];
      const double len = t.norm();
      MF_REQUIRE(len > 0.0, "edge_points: edge ", k, " of element ", b.element,
                 " has zero length at s = ", s);
      out.x.push_back(x);
      out.weight.push_back(g.weights[q] * len);
      out.normal.emplace_back(t.y() / len, -t.x() / len); // the body is on the left
      out.edge.push_back(static_cast<int>(k));
      append_row(en, N, nullptr, out.node, out.phi, nullptr, out.offset);
    }
  }
  return out;
}

Vec2 map_to_physical(const Mesh& mesh, int element, const Vec2& xi) {
  double N[kMaxElementNodes];
  shape_functions(mesh.type, xi, N, nullptr);
  const int* n = mesh.element(element);
  Vec2 x = Vec2::Zero();
  for (int a = 0; a < mesh.nodes_per_element(); ++a) x += N[a] * mesh.x[n[a]];
  return x;
}

namespace {

constexpr double kInsideTolerance = 1e-9; // natural coordinates

bool inside_reference(ElementType type, const Vec2& xi, double tol) {
  if (type == ElementType::T3)
    return xi.x() >= -tol && xi.y() >= -tol && xi.x() + xi.y() <= 1.0 + tol;
  return std::abs(xi.x()) <= 1.0 + tol && std::abs(xi.y()) <= 1.0 + tol;
}

/// Newton's method on x(xi) = x from the element's centre. False if it leaves the neighbourhood
/// of the reference element, meets det J <= 0 or does not converge: x is then not in it.
bool inverse_map(const Mesh& mesh, int e, const Vec2& x, Vec2& xi) {
  ElementNodes en;
  en.gather(mesh, e);
  double N[kMaxElementNodes];
  Vec2 dN[kMaxElementNodes];
  Vec2 z = mesh.type == ElementType::T3 ? Vec2(1.0 / 3.0, 1.0 / 3.0) : Vec2(0.0, 0.0);
  for (int it = 0; it < 30; ++it) {
    shape_functions(mesh.type, z, N, dN);
    Vec2 r = -x;
    for (int a = 0; a < en.count; ++a) r += N[a] * en.x[a];
    const Mat2 J = jacobian(en, dN);
    const double det = J.determinant();
    if (!(det > 0.0)) return false;
    const Vec2 step = J.inverse() * r;
    z -= step;
    if (!inside_reference(mesh.type, z, 1.0)) return false; // wandered off: not this element
    // Quadratic convergence: after a step this small the error is at rounding level (a test
    // on the residual would depend on the coordinates' magnitude).
    if (step.lpNorm<Eigen::Infinity>() < 1e-10) {
      xi = z;
      return true;
    }
  }
  return false;
}

} // namespace

PointLocator::PointLocator(const Mesh& mesh) : mesh_(&mesh) {
  check_mesh(mesh, "PointLocator");
  const int ne = mesh.element_count();
  const int nc = corners_per_element(mesh.type);
  box_.resize(ne);
  std::vector<Vec2> centre(ne);
  std::vector<double> radius(ne);
  double rmin = 0.0;
  for (int e = 0; e < ne; ++e) {
    const int* n = mesh.element(e);
    BoundingBox b{mesh.x[n[0]], mesh.x[n[0]]};
    auto grow = [&](const Vec2& p) { b.lo = b.lo.cwiseMin(p), b.hi = b.hi.cwiseMax(p); };
    for (int a = 0; a < mesh.nodes_per_element(); ++a) grow(mesh.x[n[a]]);
    if (mesh.type == ElementType::Q8)
      // A quadratic edge lies in the hull of its Bezier control points: the ends and
      // 2 m - (a + b) / 2; the element lies inside its edges.
      for (int k = 0; k < nc; ++k)
        grow(2.0 * mesh.x[n[nc + k]] - 0.5 * (mesh.x[n[k]] + mesh.x[n[(k + 1) % nc]]));
    box_[e] = b;
    centre[e] = 0.5 * (b.lo + b.hi);
    radius[e] = 0.5 * b.size().norm();
    MF_REQUIRE(radius[e] > 0.0, "PointLocator: ", describe(mesh, e), " has zero size");
    rmin = e == 0 ? radius[e] : std::min(rmin, radius[e]);
  }
  // Groups of elements whose radii lie within a factor of 2: [rmin 2^k, rmin 2^(k+1)).
  std::vector<int> group_of(ne);
  int groups = 0;
  for (int e = 0; e < ne; ++e) {
    group_of[e] = static_cast<int>(std::floor(std::log2(radius[e] / rmin)));
    groups = std::max(groups, group_of[e] + 1);
  }
  std::vector<SizeGroup> all(groups);
  std::vector<std::vector<Vec2>> points(groups);
  for (int e = 0; e < ne; ++e) {
    SizeGroup& g = all[group_of[e]];
    g.element.push_back(e);
    g.radius = std::max(g.radius, radius[e]);
    points[group_of[e]].push_back(centre[e]);
  }
  for (int k = 0; k < groups; ++k)
    if (!all[k].element.empty()) {
      all[k].grid = neighbors::PointGrid(points[k], all[k].radius);
      groups_.push_back(std::move(all[k]));
    }
}

bool PointLocator::locate(const Vec2& x, int& element, Vec2& xi) const {
  const Mesh& mesh = *mesh_;
  bool found = false;
  for (const SizeGroup& g : groups_) {
    // An element that holds x has its box centre within its half-diagonal of x.
    g.grid.for_each_within(x, g.radius * (1.0 + 1e-6), [&](int k) {
      if (found) return;
      const int e = g.element[k];
      const BoundingBox& b = box_[e];
      if (!b.contains(x, 1e-6 * b.size().maxCoeff())) return;
      Vec2 z;
      if (inverse_map(mesh, e, x, z) && inside_reference(mesh.type, z, kInsideTolerance)) {
        found = true;
        element = e;
        xi = z;
      }
    });
    if (found) return true;
  }
  return false;
}

PointShapes shapes_at(const Mesh& mesh, const PointLocator& locator,
                      const std::vector<Vec2>& points, bool gradients) {
  PointShapes out;
  const int npe = mesh.nodes_per_element();
  const std::size_t rows = points.size();
  out.x.reserve(rows);
  out.element.reserve(rows);
  out.offset.reserve(rows + 1);
  out.node.reserve(rows * npe);
  out.phi.reserve(rows * npe);
  if (gradients) out.dphi.reserve(rows * npe);
  ElementNodes en;
  double N[kMaxElementNodes];
  Vec2 dN[kMaxElementNodes], dN_dx[kMaxElementNodes];
  for (std::size_t i = 0; i < points.size(); ++i) {
    int e = -1;
    Vec2 xi;
    MF_REQUIRE(locator.locate(points[i], e, xi), "fem: point ", i, " (", points[i].x(), ", ",
               points[i].y(), ") lies in no element of the mesh");
    en.gather(mesh, e);
    shape_functions(mesh.type, xi, N, dN);
    if (gradients) {
      const Mat2 J = jacobian(en, dN);
      const double det = J.determinant();
      if (!(det > 0.0)) bad_jacobian(mesh, e, xi, det);
      const Mat2 JinvT = J.inverse().transpose();
      for (int a = 0; a < npe; ++a) dN_dx[a] = JinvT * dN[a];
    }
    out.x.push_back(points[i]);
    out.element.push_back(e);
    append_row(en, N, gradients ? dN_dx : nullptr, out.node, out.phi,
               gradients ? &out.dphi : nullptr, out.offset);
  }
  return out;
}

} // namespace mf::fem
