// Finite elements: shape functions, quadrature, integration and boundary points, the gmsh
// reader, the point locator and node ordering.
#include "meshfree/core/error.hpp"
#include "meshfree/fem/elements.hpp"
#include "meshfree/fem/mesh.hpp"
#include "test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>

using namespace mf;
using fem::ElementType;

namespace {

const ElementType kTypes[] = {ElementType::T3, ElementType::Q4, ElementType::Q8};

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// A random natural point inside the reference element.
Vec2 random_natural(ElementType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  if (type != ElementType::T3) return {u(rng), u(rng)};
  Vec2 p(0.5 * (1 + u(rng)), 0.5 * (1 + u(rng)));
  if (p.x() + p.y() > 1.0) p = Vec2(1.0 - p.x(), 1.0 - p.y());
  return p;
}

/// A structured mesh of [0, 2] x [0, 1] with every node moved by up to `amplitude` times the
/// cell size (Q8 mid-side nodes by half that, which curves the edges, the outline's included).
/// With `straight`, Q8 mid-side nodes are put back at the middle of their (moved) edges.
fem::Mesh distorted(ElementType type, int nx, int ny, double amplitude, unsigned seed,
                    bool straight = false) {
  fem::Mesh m = fem::structured_rectangle({0, 0}, {2, 1}, nx, ny, type);
  const double h = std::min(2.0 / nx, 1.0 / ny);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int nc = fem::corners_per_element(type);
  std::vector<char> corner(m.node_count(), 0);
  for (int e = 0; e < m.element_count(); ++e)
    for (int k = 0; k < nc; ++k) corner[m.element(e)[k]] = 1;
  for (int i = 0; i < m.node_count(); ++i) {
    const double a = corner[i] ? amplitude : 0.5 * amplitude;
    m.x[i] += a * h * Vec2(u(rng), u(rng));
  }
  if (type == ElementType::Q8 && straight)
    for (int e = 0; e < m.element_count(); ++e) {
      const int* n = m.element(e);
      for (int k = 0; k < 4; ++k) m.x[n[4 + k]] = 0.5 * (m.x[n[k]] + m.x[n[(k + 1) % 4]]);
    }
  return m;
}

/// Area enclosed by the mesh outline: straight edges by the shoelace formula; a quadratic edge
/// adds the parabolic segment between its chord and itself, 4/3 of the triangle (a, m, b)
/// (Archimedes' quadrature of the parabola; m is at the parameter midpoint, where the tangent
/// is parallel to the chord). Independent of the element integration.
double outline_area(const fem::Mesh& m) {
  double area = 0.0;
  for (const auto& b : fem::boundary_edges(m)) {
    const Vec2 &a = m.x[b.nodes[0]], &c = m.x[b.nodes[1]];
    area += 0.5 * cross(a, c);
    if (b.count == 3) area += (4.0 / 3.0) * 0.5 * cross(m.x[b.nodes[2]] - a, c - a);
  }
  return area;
}

/// Integrals of 1, x^2, xy, y^2 over a polygon (the standard vertex formulas from Green's
/// theorem, e.g. Steger 1996, "On the calculation of arbitrary moments of polygons").
std::array<double, 4> polygon_moments(const std::vector<Vec2>& p) {
  std::array<double, 4> s{0, 0, 0, 0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % p.size()];
    const double c = cross(a, b);
    s[0] += c / 2;
    s[1] += c * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) / 12;
    s[2] += c * (a.x() * b.y() + 2 * a.x() * a.y() + 2 * b.x() * b.y() + b.x() * a.y()) / 24;
    s[3] += c * (a.y() * a.y() + a.y() * b.y() + b.y() * b.y()) / 12;
  }
  return s;
}

/// Largest difference, over the nodes, between the two sides of the discrete divergence
/// theorem: sum_q w_q dphi_I(x_q) = sum_edge-points w phi_I n. Exact (to rounding) when both
/// rules integrate their polynomial integrands exactly.
double divergence_mismatch(const fem::Mesh& m, int order, int edge_order) {
  const fem::PointShapes d = fem::domain_points(m, order);
  const fem::EdgePoints b = fem::edge_points(m, fem::boundary_edges(m), edge_order);
  std::vector<Vec2> lhs(m.node_count(), Vec2::Zero()), rhs(m.node_count(), Vec2::Zero());
  for (int q = 0; q < d.rows(); ++q)
    for (int k = d.offset[q]; k < d.offset[q + 1]; ++k) lhs[d.node[k]] += d.weight[q] * d.dphi[k];
  for (int q = 0; q < b.rows(); ++q)
    for (int k = b.offset[q]; k < b.offset[q + 1]; ++k)
      rhs[b.node[k]] += b.weight[q] * b.phi[k] * b.normal[q];
  double worst = 0.0;
  for (int i = 0; i < m.node_count(); ++i) worst = std::max(worst, (lhs[i] - rhs[i]).norm());
  return worst;
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

/// Largest node-number spread within an element.
int bandwidth(const fem::Mesh& m) {
  int bw = 0;
  for (int e = 0; e < m.element_count(); ++e) {
    const int* n = m.element(e);
    const auto [lo, hi] = std::minmax_element(n, n + m.nodes_per_element());
    bw = std::max(bw, *hi - *lo);
  }
  return bw;
}

std::string data(const std::string& name) {
  return source_path("tests/data/" + name);
}

/// A file in the system's temporary folder with the given text.
std::string temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("meshfree_test_fem_" + name);
  std::ofstream(path) << text;
  return path.string();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The message of the mf::Error that f throws ("" if none).
template <class F> std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

} // namespace

TEST_CASE("element shape functions: Kronecker delta, partition of unity, polynomial "
          "reproduction, derivatives",
          "[fem]") {
  std::mt19937 rng(7);
  for (ElementType type : kTypes) {
    INFO(fem::element_name(type));
    const int n = fem::nodes_per_element(type);
    const Vec2* xa = fem::reference_nodes(type);
    double N[8], Np[8], Nm[8];
    Vec2 dN[8];
    double delta_err = 0.0;
    for (int b = 0; b < n; ++b) {
      fem::shape_functions(type, xa[b], N, nullptr);
      for (int a = 0; a < n; ++a) delta_err = std::max(delta_err, std::abs(N[a] - (a == b)));
    }
    CHECK(delta_err < 1e-15);
    double unity = 0, linear = 0, quadratic = 0, grad_unity = 0, grad_linear = 0, fd = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const Vec2 xi = random_natural(type, rng);
      fem::shape_functions(type, xi, N, dN);
      double s = 0;
      Vec2 x = Vec2::Zero(), g = Vec2::Zero();
      Mat2 G = Mat2::Zero();
      for (int a = 0; a < n; ++a) {
        s += N[a], x += N[a] * xa[a], g += dN[a], G += xa[a] * dN[a].transpose();
      }
      unity = std::max(unity, std::abs(s - 1));
      linear = std::max(linear, (x - xi).norm());
      grad_unity = std::max(grad_unity, g.norm());
      grad_linear = std::max(grad_linear, (G - Mat2::Identity()).norm());
      // Q4 reproduces xi*eta; Q8 the complete quadratic xi^2, xi*eta, eta^2.
      if (type != ElementType::T3) {
        double f[3] = {0, 0, 0};
        for (int a = 0; a < n; ++a) {
          f[0] += N[a] * xa[a].x() * xa[a].y();
          f[1] += N[a] * xa[a].x() * xa[a].x();
          f[2] += N[a] * xa[a].y() * xa[a].y();
        }
        quadratic = std::max(quadratic, std::abs(f[0] - xi.x() * xi.y()));
        if (type == ElementType::Q8) {
          quadratic = std::max(quadratic, std::abs(f[1] - xi.x() * xi.x()));
          quadratic = std::max(quadratic, std::abs(f[2] - xi.y() * xi.y()));
        }
      }
      const double h = 1e-6;
      for (int d = 0; d < 2; ++d) {
        const Vec2 e = h * Vec2::Unit(d);
        fem::shape_functions(type, xi + e, Np, nullptr);
        fem::shape_functions(type, xi - e, Nm, nullptr);
        for (int a = 0; a < n; ++a)
          fd = std::max(fd, std::abs((Np[a] - Nm[a]) / (2 * h) - dN[a][d]));
      }
    }
    CHECK(unity < 1e-14);
    CHECK(linear < 1e-14);
    CHECK(grad_unity < 1e-13);
    CHECK(grad_linear < 1e-13);
    CHECK(quadratic < 1e-14);
    CHECK(fd < 1e-7);
  }
}

TEST_CASE("Q8 on an affine element reproduces x^2, xy, y^2 and their gradients in physical "
          "space",
          "[fem]") {
  fem::Mesh m = fem::structured_rectangle({0, 0}, {2, 1}, 3, 2, ElementType::Q8);
  Mat2 A;
  A << 1.2, 0.5, -0.3, 0.9; // one affine map for the whole mesh: every element is affine
  for (Vec2& p : m.x) p = A * p + Vec2(0.7, -0.2);
  const fem::PointShapes s = fem::domain_points(m, 3);
  auto f = [](const Vec2& x) { return Vec3(x.x() * x.x(), x.x() * x.y(), x.y() * x.y()); };
  double value = 0, grad = 0;
  for (int q = 0; q < s.rows(); ++q) {
    Vec3 v = Vec3::Zero();
    Eigen::Matrix<double, 3, 2> g = Eigen::Matrix<double, 3, 2>::Zero();
    for (int k = s.offset[q]; k < s.offset[q + 1]; ++k) {
      v += s.phi[k] * f(m.x[s.node[k]]);
      g += f(m.x[s.node[k]]) * s.dphi[k].transpose();
    }
    const Vec2 x = s.x[q];
    Eigen::Matrix<double, 3, 2> exact;
    exact << 2 * x.x(), 0, x.y(), x.x(), 0, 2 * x.y();
    value = std::max(value, (v - f(x)).norm());
    grad = std::max(grad, (g - exact).norm());
  }
  CHECK(value < 1e-13);
  CHECK(grad < 1e-12);
}

TEST_CASE("reference rules integrate the polynomials they promise exactly", "[fem]") {
  auto fact = [](int k) { return std::tgamma(k + 1.0); };
  for (int degree = 1; degree <= 8; ++degree) { // triangles: order = degree
    const fem::ReferenceRule r = fem::domain_rule(ElementType::T3, degree);
    double err = 0;
    for (int p = 0; p <= degree; ++p)
      for (int q = 0; p + q <= degree; ++q) {
        double s = 0;
        for (std::size_t k = 0; k < r.xi.size(); ++k)
          s += r.weight[k] * std::pow(r.xi[k].x(), p) * std::pow(r.xi[k].y(), q);
        err = std::max(err, std::abs(s - fact(p) * fact(q) / fact(p + q + 2)));
      }
    INFO("triangle degree " << degree);
    CHECK(err < 1e-15);
    CHECK(*std::min_element(r.weight.begin(), r.weight.end()) > 0);
    for (const Vec2& xi : r.xi) CHECK((xi.x() >= 0 && xi.y() >= 0 && xi.x() + xi.y() <= 1));
  }
  CHECK(fem::domain_rule(ElementType::T3, 1).xi.size() == 1);
  CHECK(fem::domain_rule(ElementType::T3, 2).xi.size() == 3);
  CHECK(fem::domain_rule(ElementType::T3, 5).xi.size() == 7);
  for (int n = 1; n <= 4; ++n) { // quads: n x n Gauss, exact to degree 2n - 1 in each variable
    const fem::ReferenceRule r = fem::domain_rule(ElementType::Q8, n);
    REQUIRE(r.xi.size() == static_cast<std::size_t>(n * n));
    auto exact1 = [](int p) { return p % 2 ? 0.0 : 2.0 / (p + 1); };
    double err = 0;
    for (int p = 0; p <= 2 * n - 1; ++p)
      for (int q = 0; q <= 2 * n - 1; ++q) {
        double s = 0;
        for (std::size_t k = 0; k < r.xi.size(); ++k)
          s += r.weight[k] * std::pow(r.xi[k].x(), p) * std::pow(r.xi[k].y(), q);
        err = std::max(err, std::abs(s - exact1(p) * exact1(q)));
      }
    CHECK(err < 1e-14);
  }
  CHECK(fem::default_order(ElementType::T3) == 1);
  CHECK(fem::default_order(ElementType::Q4) == 2);
  CHECK(fem::default_order(ElementType::Q8) == 3);
  CHECK_THROWS_AS(fem::domain_rule(ElementType::Q4, 0), Error);
}

TEST_CASE("domain points: areas and moments exact on structured, distorted and curved meshes",
          "[fem]") {
  // Rectangle [1, 4] x [2, 4]: area 6, integral of xy = 7.5 * 6 = 45.
  for (ElementType type : kTypes) {
    INFO(fem::element_name(type));
    const fem::Mesh m = fem::structured_rectangle({1, 2}, {3, 2}, 7, 5, type);
    CHECK(m.element_count() == (type == ElementType::T3 ? 70 : 35));
    CHECK(m.node_count() == (type == ElementType::Q8 ? 15 * 11 - 35 : 8 * 6));
    const int order = type == ElementType::T3 ? 2 : fem::default_order(type);
    const fem::PointShapes s = fem::domain_points(m, order);
    double xy = 0;
    for (int q = 0; q < s.rows(); ++q) xy += s.weight[q] * s.x[q].x() * s.x[q].y();
    CHECK(std::abs(sum(s.weight) - 6.0) < 1e-13);
    CHECK(std::abs(xy - 45.0) < 1e-12);
  }
  // Distorted straight-sided elements: 1, x^2, xy, y^2 against the polygon formulas element by
  // element (Q4 2x2 is exact for the bilinear map's degree-3 integrands; T3 needs the degree-2
  // rule; Q8 with mid-side nodes at mid-edge is the bilinear map again).
  for (ElementType type : kTypes) {
    INFO(fem::element_name(type));
    const fem::Mesh m = distorted(type, 6, 4, 0.15, 11, true);
    const int order = type == ElementType::T3 ? 2 : fem::default_order(type);
    const fem::PointShapes s = fem::domain_points(m, order);
    std::array<double, 4> got{0, 0, 0, 0}, want{0, 0, 0, 0};
    for (int q = 0; q < s.rows(); ++q) {
      const Vec2 x = s.x[q];
      const double f[4] = {1.0, x.x() * x.x(), x.x() * x.y(), x.y() * x.y()};
      for (int k = 0; k < 4; ++k) got[k] += s.weight[q] * f[k];
    }
    const int nc = fem::corners_per_element(type);
    for (int e = 0; e < m.element_count(); ++e) {
      std::vector<Vec2> poly;
      for (int k = 0; k < nc; ++k) poly.push_back(m.x[m.element(e)[k]]);
      const auto pm = polygon_moments(poly);
      for (int k = 0; k < 4; ++k) want[k] += pm[k];
    }
    for (int k = 0; k < 4; ++k) CHECK(std::abs(got[k] - want[k]) < 1e-12);
    CHECK(std::abs(got[0] - 2.0) < 0.2); // the distortion kept the body near [0, 2] x [0, 1]
  }
  // Curved Q8 edges (mid-side nodes off the chords, the outline's included): the sum of the
  // weights is the area inside the quadratic outline (3x3 Gauss is exact for det J, degree 3 in
  // each variable).
  const fem::Mesh curved = distorted(ElementType::Q8, 6, 4, 0.15, 12);
  const fem::PointShapes s = fem::domain_points(curved, 3);
  const double enclosed = outline_area(curved);
  CHECK(std::abs(sum(s.weight) - enclosed) < 1e-12);
  double straight = 0; // the curvature matters: the corner polygons miss a measurable area
  for (int e = 0; e < curved.element_count(); ++e) {
    std::vector<Vec2> poly;
    for (int k = 0; k < 4; ++k) poly.push_back(curved.x[curved.element(e)[k]]);
    straight += polygon_moments(poly)[0];
  }
  CHECK(std::abs(straight - enclosed) > 1e-3);
}

TEST_CASE("domain points: nodes sorted, rows complete, inverted elements named", "[fem]") {
  fem::Mesh m = distorted(ElementType::Q8, 3, 2, 0.1, 3);
  const fem::PointShapes s = fem::domain_points(m, 3);
  REQUIRE(s.rows() == 9 * m.element_count());
  CHECK(s.x.size() == 9u * m.element_count());
  CHECK(s.dphi.size() == s.node.size());
  for (int q = 0; q < s.rows(); ++q) {
    REQUIRE(s.offset[q + 1] - s.offset[q] == 8);
    CHECK(std::is_sorted(s.node.begin() + s.offset[q], s.node.begin() + s.offset[q + 1]));
    CHECK(s.element[q] == q / 9);
  }
  std::swap(m.connectivity[8 * 4 + 1], m.connectivity[8 * 4 + 3]); // element 4 turned inside out
  const std::string msg = error_of([&] { fem::domain_points(m, 3); });
  CHECK(contains(msg, "element 4 (nodes"));
  CHECK(contains(msg, "det J"));
}

TEST_CASE("boundary edges of a structured rectangle: count, counter-clockwise, perimeter",
          "[fem]") {
  for (ElementType type : kTypes) {
    INFO(fem::element_name(type));
    const Vec2 lo(1, 2), size(3, 2), centre = lo + 0.5 * size;
    const fem::Mesh m = fem::structured_rectangle(lo, size, 4, 3, type);
    const auto edges = fem::boundary_edges(m);
    CHECK(edges.size() == 14u);
    double length = 0;
    std::vector<int> starts(m.node_count(), 0), ends(m.node_count(), 0);
    for (const auto& b : edges) {
      const Vec2 &a = m.x[b.nodes[0]], &c = m.x[b.nodes[1]];
      length += (c - a).norm();
      CHECK(cross(c - a, centre - a) > 0); // the body on the left
      CHECK(b.count == (type == ElementType::Q8 ? 3 : 2));
      if (b.count == 3) CHECK((m.x[b.nodes[2]] - 0.5 * (a + c)).norm() < 1e-15);
      ++starts[b.nodes[0]], ++ends[b.nodes[1]];
    }
    CHECK(std::abs(length - 10.0) < 1e-13);
    CHECK(starts == ends); // a closed outline: every node entered as often as left
    const fem::EdgePoints p = fem::edge_points(m, edges, fem::default_edge_order(type));
    CHECK(p.rows() == 14 * fem::default_edge_order(type));
    CHECK(std::abs(sum(p.weight) - 10.0) < 1e-13);
    for (int q = 0; q < p.rows(); ++q) {
      const Vec2 n = p.normal[q], r = p.x[q] - centre;
      // outward: along the axis whose side the point is on
      const Vec2 want = std::abs(std::abs(r.x()) - 1.5) < 1e-12 ? Vec2(r.x() > 0 ? 1 : -1, 0)
                                                                : Vec2(0, r.y() > 0 ? 1 : -1);
      CHECK((n - want).norm() < 1e-15);
    }
  }
}

TEST_CASE("discrete divergence theorem ties domain and edge points on distorted meshes", "[fem]") {
  // T3: constant gradients; Q4: 2x2 exact for the cofactor terms (degree 2 per variable);
  // Q8 with curved edges: cofactor times dN is degree 3 per variable, 3x3 exact; edges: phi
  // times the (unnormalised) normal is degree 3 in s, so 2 points suffice.
  CHECK(divergence_mismatch(distorted(ElementType::T3, 6, 4, 0.15, 21), 1, 1) < 1e-13);
  CHECK(divergence_mismatch(distorted(ElementType::Q4, 6, 4, 0.15, 22), 2, 2) < 1e-13);
  CHECK(divergence_mismatch(distorted(ElementType::Q8, 6, 4, 0.15, 23), 3, 2) < 1e-13);
  // An under-integrated Q8 (1 point) breaks it: the check can fail.
  CHECK(divergence_mismatch(distorted(ElementType::Q8, 6, 4, 0.15, 23), 1, 2) > 1e-4);
}

TEST_CASE("structured meshes: sizes, renumbering and errors", "[fem]") {
  CHECK(fem::characteristic_size(fem::structured_rectangle(
            {0, 0}, {4, 2}, 4, 2, ElementType::Q4)) == Approx(1.0).epsilon(1e-14));
  CHECK(
      fem::characteristic_size(fem::structured_rectangle({0, 0}, {4, 2}, 4, 2, ElementType::T3)) ==
      Approx((2 + std::sqrt(2.0)) / 3).epsilon(1e-14));
  CHECK(fem::characteristic_size(fem::structured_rectangle(
            {0, 0}, {4, 2}, 4, 2, ElementType::Q8)) == Approx(1.0).epsilon(1e-14));
  CHECK(contains(error_of([] {
                   fem::structured_rectangle({0, 0}, {1, 1}, 0, 2, ElementType::Q4);
                 }),
                 "at least one cell"));
  CHECK(std::string(fem::element_name(ElementType::Q8)) == "Q8");
  // A clockwise element is reversed with its mid-side nodes following their edges.
  fem::Mesh m = fem::structured_rectangle({0, 0}, {1, 1}, 1, 1, ElementType::Q8);
  const std::vector<int> ccw = m.connectivity;
  const int* n = ccw.data();
  m.connectivity = {n[0], n[3], n[2], n[1], n[7], n[6], n[5], n[4]};
  CHECK(fem::signed_area(m, 0) < 0);
  CHECK(fem::orient_counter_clockwise(m, "test") == 1);
  CHECK(fem::signed_area(m, 0) == Approx(1.0).epsilon(1e-14));
  CHECK(std::abs(sum(fem::domain_points(m, 3).weight) - 1.0) < 1e-14);
  for (int k = 0; k < 4; ++k) // mid-side node k between corners k and k + 1
    CHECK((m.x[m.element(0)[4 + k]] - 0.5 * (m.x[m.element(0)[k]] + m.x[m.element(0)[(k + 1) % 4]]))
              .norm() < 1e-15);
}

TEST_CASE("gmsh: the plate with a hole in MSH 2.2 and 4.1", "[fem]") {
  const double R = 1.0, exact = 25.0 - M_PI / 4; // quarter of a 10 x 10 plate, hole radius 1
  struct Case {
    const char* name;
    ElementType type;
    int nodes, elements;
  };
  for (const Case& c :
       {Case{"t3", ElementType::T3, 200, 350}, Case{"q8", ElementType::Q8, 873, 272}}) {
    INFO(c.name);
    const fem::Mesh m22 = fem::read_gmsh(data(std::string("plate_hole_") + c.name + "_v22.msh"));
    const fem::Mesh m41 = fem::read_gmsh(data(std::string("plate_hole_") + c.name + "_v41.msh"));
    CHECK(m22.type == c.type);
    CHECK(m22.node_count() == c.nodes);
    CHECK(m22.element_count() == c.elements);
    CHECK(m41.type == c.type);
    CHECK(m41.x == m22.x);
    CHECK(m41.connectivity == m22.connectivity);
    for (int e = 0; e < m22.element_count(); ++e) CHECK(fem::signed_area(m22, e) > 0);

    // The arc nodes lie on the circle; straight boundary parts have length 18.
    const auto edges = fem::boundary_edges(m22);
    double straight = 0;
    std::vector<const fem::BoundaryEdge*> arc;
    for (const auto& b : edges) {
      const Vec2 &a = m22.x[b.nodes[0]], &z = m22.x[b.nodes[1]];
      if (std::abs(a.norm() - R) < 1e-6 && std::abs(z.norm() - R) < 1e-6) {
        arc.push_back(&b);
        for (int k = 0; k < b.count; ++k) CHECK(std::abs(m22.x[b.nodes[k]].norm() - R) < 1e-12);
      } else {
        straight += (z - a).norm();
      }
    }
    CHECK(std::abs(straight - 18.0) < 1e-12);
    CHECK(arc.size() == 8u); // size 0.2 on an arc of length pi/2

    // Area: the mesh differs from the body only at the hole, whose mesh outline runs inside the
    // circle and so adds a known sliver per arc edge of angle theta: for T3 the circular segment
    // R^2 (theta - sin theta) / 2 off a chord; for Q8 the parabola through the ends and the
    // angular mid-point encloses R^2 sin(a) (1 + (1 - cos a) / 3) with the centre (a = theta / 2,
    // from 1/2 of the integral of x dy - y dx along the quadratic edge) against the sector's
    // R^2 a, about R^2 theta^5 / 960 less. Without the slivers the areas differ by 5e-3 (T3) and
    // 2.4e-6 (Q8); with them they agree to the rounding of the node coordinates (16 digits).
    const double area = sum(fem::domain_points(m22, fem::default_order(c.type)).weight);
    double sliver = 0;
    for (const auto* b : arc) {
      const double theta =
          std::acos(std::clamp(m22.x[b->nodes[0]].dot(m22.x[b->nodes[1]]) / (R * R), -1.0, 1.0));
      const double a = theta / 2;
      sliver += c.type == ElementType::T3 ? 0.5 * R * R * (theta - std::sin(theta))
                                          : R * R * (a - std::sin(a) * (1 + (1 - std::cos(a)) / 3));
    }
    INFO("area " << area << ", exact " << exact << ", sliver " << sliver);
    CHECK(std::abs(area - sliver - exact) < 1e-12);
    CHECK(sliver > 1e-6); // far above the tolerance: leaving it out would fail
    CHECK(std::abs(area - outline_area(m22)) < 1e-12);

    // Domain and edge points agree (the discrete divergence theorem).
    CHECK(divergence_mismatch(m22, fem::default_order(c.type), 2) < 1e-13);
  }
}

TEST_CASE("gmsh: sparse tags, parametric nodes, unused nodes and clockwise elements", "[fem]") {
  const fem::Mesh m = fem::read_gmsh(data("small_v41.msh"));
  CHECK(m.type == ElementType::Q4);
  CHECK(m.node_count() == 6); // node 99 is used by no element
  REQUIRE(m.element_count() == 2);
  CHECK(m.connectivity == std::vector<int>{0, 1, 4, 3, 1, 2, 5, 4}); // the second one reversed
  CHECK(m.x[5] == Vec2(2, 1));
}

TEST_CASE("gmsh: bad files give errors that name the file", "[fem]") {
  const std::string missing = data("no_such_mesh.msh");
  const std::string e1 = error_of([&] { fem::read_gmsh(missing); });
  CHECK(contains(e1, missing));
  CHECK(contains(e1, "cannot open"));

  const std::string mixed = data("mixed_types_v22.msh");
  const std::string e2 = error_of([&] { fem::read_gmsh(mixed); });
  CHECK(contains(e2, mixed));
  CHECK(contains(e2, "mixes 2-D element types Q4 (element 1) and T3 (element 2)"));

  for (const char* name : {"plate_hole_q8_v22.msh", "plate_hole_q8_v41.msh"}) {
    const std::string text = read_text(data(name));
    // Cut inside $Elements (the last fifth of both files): at a line end, the element count is
    // not reached; within a line, that element has too few nodes.
    const std::size_t at = text.rfind('\n', text.size() * 9 / 10) + 1;
    const std::string cut = temp_file(std::string("cut_") + name, text.substr(0, at));
    const std::string e3 = error_of([&] { fem::read_gmsh(cut); });
    CHECK(contains(e3, cut));
    CHECK(contains(e3, "cut short"));
    const std::string torn = temp_file(std::string("torn_") + name, text.substr(0, at - 6));
    const std::string e4 = error_of([&] { fem::read_gmsh(torn); });
    CHECK(contains(e4, torn));
    CHECK(contains(e4, "nodes instead of 8"));
  }

  const std::string small = read_text(data("small_v41.msh"));
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = small;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::string v40 = temp_file("v40.msh", with("4.1 0 8", "4 0 8"));
  CHECK(
      contains(error_of([&] { fem::read_gmsh(v40); }), v40 + ":2: MSH version 4 is not supported"));
  const std::string bin = temp_file("bin.msh", with("4.1 0 8", "4.1 1 8"));
  CHECK(contains(error_of([&] { fem::read_gmsh(bin); }), "binary MSH files are not supported"));
  const std::string lost = temp_file("lost.msh", with("3 11 14 15 12", "3 11 14 15 16"));
  const std::string e4 = error_of([&] { fem::read_gmsh(lost); });
  CHECK(contains(e4, lost));
  CHECK(contains(e4, "element 3 names node 16, which is not in $Nodes"));
  const std::string lines = temp_file("lines.msh", with("2 1 3 2", "1 1 3 2"));
  CHECK(contains(error_of([&] { fem::read_gmsh(lines); }), "no 2-D elements"));
  const std::string t6 = temp_file("t6.msh", with("2 1 3 2", "2 1 9 2"));
  CHECK(contains(error_of([&] { fem::read_gmsh(t6); }), "lists 4 nodes instead of 6"));
  const std::string bent = temp_file("bent.msh", with("2 1 0\n", "2 1 0.5\n"));
  CHECK(contains(error_of([&] { fem::read_gmsh(bent); }), "do not lie in one plane"));
}

TEST_CASE("point locator and shapes at arbitrary points", "[fem]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Structured Q4: the containing element is known from the point.
  {
    const fem::Mesh m = fem::structured_rectangle({1, 2}, {3, 2}, 6, 4, ElementType::Q4);
    const fem::PointLocator loc(m);
    int wrong = 0;
    for (int i = 0; i < 200; ++i) {
      const int ci = i % 6, cj = (i / 6) % 4; // inside cell (ci, cj), away from its edges
      const Vec2 p(1 + 0.5 * (ci + 0.05 + 0.9 * u(rng)), 2 + 0.5 * (cj + 0.05 + 0.9 * u(rng)));
      int e = -1;
      Vec2 xi;
      REQUIRE(loc.locate(p, e, xi));
      wrong += e != cj * 6 + ci;
    }
    CHECK(wrong == 0);
    int e = -1;
    Vec2 xi;
    CHECK(loc.locate({4, 4}, e, xi));   // a corner of the body
    CHECK(loc.locate({2.5, 2}, e, xi)); // on the outline, on a node
    CHECK(!loc.locate({4 + 1e-6, 3}, e, xi));
  }
  // Distorted curved Q8 and the gmsh meshes: x(xi) returns the point; a linear field and its
  // gradient are reproduced.
  const std::vector<fem::Mesh> meshes = {
      distorted(ElementType::Q8, 6, 4, 0.15, 31), distorted(ElementType::T3, 6, 4, 0.15, 32),
      fem::read_gmsh(data("plate_hole_q8_v41.msh")), fem::read_gmsh(data("plate_hole_t3_v41.msh"))};
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    INFO("mesh " << k);
    const fem::Mesh& m = meshes[k];
    const fem::PointLocator loc(m);
    // Points: the integration points of a finer rule (strictly inside a known element), plus
    // random points for the plate.
    const fem::PointShapes inner = fem::domain_points(m, 4);
    std::vector<Vec2> pts = inner.x;
    if (k >= 2)
      while (pts.size() < 3000) {
        const Vec2 p(5 * u(rng), 5 * u(rng));
        if (p.norm() > 1.02) pts.push_back(p);
      }
    double mapped = 0, value = 0, grad = 0, outside = 0;
    int wrong = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec2& p = pts[i];
      int e = -1;
      Vec2 xi;
      REQUIRE(loc.locate(p, e, xi));
      if (i < inner.x.size()) wrong += e != inner.element[i];
      mapped = std::max(mapped, (fem::map_to_physical(m, e, xi) - p).norm());
      if (m.type == ElementType::T3)
        outside = std::max({outside, -xi.x(), -xi.y(), xi.sum() - 1});
      else
        outside = std::max(outside, xi.cwiseAbs().maxCoeff() - 1);
    }
    const fem::PointShapes s = fem::shapes_at(m, loc, pts, true);
    REQUIRE(s.rows() == static_cast<int>(pts.size()));
    auto f = [](const Vec2& x) { return 1.0 + 2.0 * x.x() - 3.0 * x.y(); };
    for (int q = 0; q < s.rows(); ++q) {
      double v = 0;
      Vec2 g = Vec2::Zero();
      for (int j = s.offset[q]; j < s.offset[q + 1]; ++j) {
        v += s.phi[j] * f(m.x[s.node[j]]);
        g += f(m.x[s.node[j]]) * s.dphi[j];
      }
      value = std::max(value, std::abs(v - f(pts[q])));
      grad = std::max(grad, (g - Vec2(2, -3)).norm());
    }
    CHECK(wrong == 0);
    CHECK(mapped < 1e-12);
    CHECK(outside < 1e-9);
    CHECK(value < 1e-12);
    CHECK(grad < 1e-10);
  }
  // Outside the body, and in the hole.
  const fem::Mesh& plate = meshes[2];
  const fem::PointLocator loc(plate);
  int e = -1;
  Vec2 xi;
  CHECK(!loc.locate({0.5, 0.5}, e, xi));
  CHECK(!loc.locate({6, 1}, e, xi));
  CHECK(loc.locate({0, 5}, e, xi));
  const std::string msg = error_of([&] {
    fem::shapes_at(plate, loc, {{2, 2}, {3, 1}, {0.25, 0.5}}, false);
  });
  CHECK(contains(msg, "point 2 (0.25, 0.5) lies in no element"));
  CHECK(fem::shapes_at(plate, loc, {{2, 2}}, false).dphi.empty());
}

TEST_CASE("sort_nodes_for_locality: the same mesh, a small bandwidth, compact node ranges",
          "[fem]") {
  fem::Mesh m = fem::read_gmsh(data("plate_hole_q8_v22.msh"));
  const double area = sum(fem::domain_points(m, 3).weight);
  const auto edges_before = fem::boundary_edges(m).size();
  // A random numbering first, so that the sorting has work to do.
  std::vector<int> perm(m.node_count());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(9));
  fem::renumber_nodes(m, perm);
  // Bounding-box area of four contiguous node ranges (a stand-in for four MPI ranks).
  auto range_boxes = [&] {
    double total = 0;
    const int n = m.node_count();
    for (int r = 0; r < 4; ++r) {
      BoundingBox b{m.x[r * n / 4], m.x[r * n / 4]};
      for (int i = r * n / 4; i < (r + 1) * n / 4; ++i)
        b.lo = b.lo.cwiseMin(m.x[i]), b.hi = b.hi.cwiseMax(m.x[i]);
      total += b.size().prod();
    }
    return total;
  };
  const int bw_random = bandwidth(m);
  const double boxes_random = range_boxes();
  fem::sort_nodes_for_locality(m, fem::characteristic_size(m));
  const int bw_sorted = bandwidth(m);
  const double boxes_sorted = range_boxes();
  INFO("bandwidth " << bw_random << " -> " << bw_sorted << ", range boxes " << boxes_random
                    << " -> " << boxes_sorted);
  CHECK(bw_random > 800);                    // of 873 nodes
  CHECK(bw_sorted < bw_random / 5);          // measured 143 (gmsh 4.8.4 mesh)
  CHECK(boxes_random > 90);                  // every range spans the whole 5 x 5 plate
  CHECK(boxes_sorted < 0.35 * boxes_random); // four strips: measured 28.9
  for (int e = 0; e < m.element_count(); ++e) CHECK(fem::signed_area(m, e) > 0);
  CHECK(std::abs(sum(fem::domain_points(m, 3).weight) - area) < 1e-12);
  CHECK(fem::boundary_edges(m).size() == edges_before);
  CHECK(divergence_mismatch(m, 3, 2) < 1e-13);
}
