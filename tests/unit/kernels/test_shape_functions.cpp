// Consistency of the meshfree approximations: RK and MLS reproduce complete polynomials of their
// basis exactly (round-off) everywhere, boundaries included; plain SPH does not at boundaries.
#include "meshfree/implicit/meshfree_space.hpp"
#include <catch2/catch.hpp>
#include <functional>

using namespace mf;
using kernels::Approximation;
using kernels::Basis;
using kernels::SupportShape;
using kernels::WindowType;

namespace {

geometry::NodeCloud lattice(int dim, int n, double jitter = 0.0) {
  geometry::NodeCloud c;
  const double h = 1.0 / (n - 1);
  unsigned seed = 12345;
  auto rnd = [&]() { // deterministic LCG in [-0.5, 0.5)
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
  };
  for (int j = 0; j < (dim == 1 ? 1 : n); ++j)
    for (int i = 0; i < n; ++i) {
      Vec2 p(i * h, dim == 1 ? 0.0 : j * h);
      const bool interior = i > 0 && i < n - 1 && (dim == 1 || (j > 0 && j < n - 1));
      if (interior) p += jitter * h * Vec2(rnd(), dim == 1 ? 0.0 : rnd());
      c.x.push_back(p);
      c.spacing.push_back(h);
      c.volume.push_back(dim == 1 ? h : h * h);
    }
  return c;
}

std::vector<Vec2> sample_points(int dim) {
  std::vector<Vec2> pts;
  const int m = dim == 1 ? 101 : 23;
  for (int j = 0; j < (dim == 1 ? 1 : m); ++j)
    for (int i = 0; i < m; ++i) pts.emplace_back(i / (m - 1.0), dim == 1 ? 0.0 : j / (m - 1.0));
  return pts;
}

struct FieldError {
  double value = 0.0, gradient = 0.0, boundary_value = 0.0;
};

/// Max error of the approximation of f (and its gradient) over the sample points, from nodal
/// values.
FieldError approximation_error(const implicit::MeshfreeSpace& space, int dim,
                               const std::function<double(const Vec2&)>& f,
                               const std::function<Vec2(const Vec2&)>& grad) {
  const auto pts = sample_points(dim);
  std::vector<int> rows(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) rows[i] = static_cast<int>(i);
  const auto t = space.shape_table(pts, rows, space.support_lists(pts), true);
  FieldError e;
  for (int r = 0; r < t.rows(); ++r) {
    double v = 0.0;
    Vec2 g = Vec2::Zero();
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
      const double fi = f(space.nodes().x[t.node[k]]);
      v += t.phi[k] * fi;
      g += t.dphi[k] * fi;
    }
    const Vec2 ge = grad(pts[r]);
    const double ev = std::abs(v - f(pts[r]));
    e.value = std::max(e.value, ev);
    e.gradient = std::max(e.gradient, dim == 1 ? std::abs(g.x() - ge.x()) : (g - ge).norm());
    const bool on_boundary = pts[r].x() == 0.0 || pts[r].x() == 1.0 ||
                             (dim == 2 && (pts[r].y() == 0.0 || pts[r].y() == 1.0));
    if (on_boundary) e.boundary_value = std::max(e.boundary_value, ev);
  }
  return e;
}

kernels::ShapeSettings settings(Approximation a, Basis b, WindowType w, SupportShape s, int dim) {
  kernels::ShapeSettings k;
  k.approximation = a;
  k.basis = b;
  k.window.type = w;
  k.support = s;
  k.dim = dim;
  return k;
}

const auto linear_f = [](const Vec2& x) { return 1.0 + 2.0 * x.x() + x.y(); };
const auto linear_g = [](const Vec2&) { return Vec2(2.0, 1.0); };
const auto quad_f = [](const Vec2& x) {
  return 2.0 * x.x() * x.x() + x.y() * x.y() - x.x() * x.y() + 0.5;
};
const auto quad_g = [](const Vec2& x) { return Vec2(4.0 * x.x() - x.y(), 2.0 * x.y() - x.x()); };

} // namespace

TEST_CASE("RK and MLS with a linear basis reproduce linear fields and their gradients to round-off",
          "[kernels]") {
  for (int dim : {1, 2})
    for (auto approx : {Approximation::ReproducingKernel, Approximation::MovingLeastSquares})
      for (auto window : {WindowType::CubicSpline, WindowType::QuarticSpline, WindowType::Gaussian})
        for (auto support : {SupportShape::Circular, SupportShape::Rectangular})
          for (double jitter : {0.0, 0.3}) {
            const implicit::MeshfreeSpace space(
                lattice(dim, 11, jitter), settings(approx, Basis::Linear, window, support, dim),
                Vec2(2.0, 2.0));
            const FieldError e = approximation_error(space, dim, linear_f, linear_g);
            INFO("dim " << dim << " approx " << int(approx) << " window " << int(window)
                        << " support " << int(support) << " jitter " << jitter);
            CHECK(e.value < 1e-12);
            CHECK(e.gradient < 1e-10);
          }
}

TEST_CASE("RK with a quadratic basis reproduces quadratic fields to round-off, a linear basis does not",
          "[kernels]") {
  for (int dim : {1, 2}) {
    const implicit::MeshfreeSpace quad(lattice(dim, 11, 0.2),
                                       settings(Approximation::ReproducingKernel, Basis::Quadratic,
                                                WindowType::CubicSpline, SupportShape::Circular,
                                                dim),
                                       Vec2(3.0, 3.0));
    const FieldError eq = approximation_error(quad, dim, quad_f, quad_g);
    CHECK(eq.value < 1e-11);
    CHECK(eq.gradient < 1e-9);
    const implicit::MeshfreeSpace lin(lattice(dim, 11, 0.2),
                                      settings(Approximation::ReproducingKernel, Basis::Linear,
                                               WindowType::CubicSpline, SupportShape::Circular,
                                               dim),
                                      Vec2(2.0, 2.0));
    CHECK(approximation_error(lin, dim, quad_f, quad_g).value > 1e-4);
  }
}

TEST_CASE("plain SPH kernel sums miss linear fields at the boundary, RK does not", "[kernels]") {
  for (int dim : {1, 2}) {
    const implicit::MeshfreeSpace sph(lattice(dim, 11),
                                      settings(Approximation::Sph, Basis::Linear,
                                               WindowType::CubicSpline, SupportShape::Circular,
                                               dim),
                                      Vec2(2.0, 2.0));
    const FieldError e = approximation_error(sph, dim, linear_f, linear_g);
    // The field ranges over [1, 4]; at a boundary SPH loses about half of the kernel mass.
    CHECK(e.boundary_value > 0.3);
    // Inside, a full support on a regular lattice holds: the normalised kernel sums to about one
    // (not exactly: the lattice sum of the cubic spline is not its integral).
    const std::vector<Vec2> mid{dim == 1 ? Vec2(0.5, 0.0) : Vec2(0.5, 0.5)};
    const auto t = sph.shape_table(mid, {0}, sph.support_lists(mid), false);
    double sum = 0.0;
    for (double v : t.phi) sum += v;
    CHECK(sum == Approx(1.0).epsilon(0.02));
  }
}

TEST_CASE("RK and MLS shape functions do not depend on where the body sits or how fine it is",
          "[kernels]") {
  // A far-off, very fine copy of the same node pattern gives the same shape functions: both
  // constructions write their basis in a frame local to the evaluation point.
  for (auto approx : {Approximation::ReproducingKernel, Approximation::MovingLeastSquares}) {
    const auto s =
        settings(approx, Basis::Quadratic, WindowType::CubicSpline, SupportShape::Circular, 2);
    const auto unit = lattice(2, 9, 0.2);
    geometry::NodeCloud tiny = unit;
    const double scale = 1e-4;
    const Vec2 shift(1000.0, -500.0);
    for (std::size_t i = 0; i < tiny.x.size(); ++i) {
      tiny.x[i] = shift + scale * tiny.x[i];
      tiny.spacing[i] *= scale;
      tiny.volume[i] *= scale * scale;
    }
    const implicit::MeshfreeSpace a(unit, s, Vec2(3.0, 3.0)), b(tiny, s, Vec2(3.0, 3.0));
    const std::vector<Vec2> xa{{0.9, 0.85}}, xb{shift + scale * xa[0]};
    const auto ta = a.shape_table(xa, {0}, a.support_lists(xa), true);
    const auto tb = b.shape_table(xb, {0}, b.support_lists(xb), true);
    REQUIRE(ta.node == tb.node);
    for (std::size_t k = 0; k < ta.phi.size(); ++k) {
      CHECK(tb.phi[k] == Approx(ta.phi[k]).margin(1e-9));
      CHECK((tb.dphi[k] * scale - ta.dphi[k]).norm() < 1e-7);
    }
  }
}

TEST_CASE("MLS (EFG) and RK shape functions coincide for uniform nodal volumes", "[kernels]") {
  const auto cloud = lattice(2, 9, 0.25);
  for (auto basis : {Basis::Linear, Basis::Quadratic}) {
    const double dil = basis == Basis::Linear ? 2.2 : 3.0;
    const implicit::MeshfreeSpace rk(cloud,
                                     settings(Approximation::ReproducingKernel, basis,
                                              WindowType::QuarticSpline, SupportShape::Circular, 2),
                                     Vec2(dil, dil));
    const implicit::MeshfreeSpace mls(cloud,
                                      settings(Approximation::MovingLeastSquares, basis,
                                               WindowType::QuarticSpline, SupportShape::Circular,
                                               2),
                                      Vec2(dil, dil));
    const auto pts = sample_points(2);
    std::vector<int> rows(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) rows[i] = static_cast<int>(i);
    const auto a = rk.shape_table(pts, rows, rk.support_lists(pts), true);
    const auto b = mls.shape_table(pts, rows, mls.support_lists(pts), true);
    REQUIRE(a.node == b.node);
    double dmax = 0.0;
    for (std::size_t k = 0; k < a.phi.size(); ++k)
      dmax =
          std::max({dmax, std::abs(a.phi[k] - b.phi[k]), (a.dphi[k] - b.dphi[k]).norm() * 0.125});
    CHECK(dmax < 1e-9);
  }
}

TEST_CASE("analytic shape-function gradients match central differences", "[kernels]") {
  const auto cloud = lattice(2, 9, 0.3);
  for (auto approx : {Approximation::ReproducingKernel, Approximation::MovingLeastSquares})
    for (auto window : {WindowType::CubicSpline, WindowType::Gaussian})
      for (auto support : {SupportShape::Circular, SupportShape::Rectangular}) {
        const auto s = settings(approx, Basis::Quadratic, window, support, 2);
        const implicit::MeshfreeSpace space(cloud, s, Vec2(3.1, 3.1));
        const auto view = space.view();
        const Vec2 x(0.4321, 0.1234);
        std::vector<int> nb;
        space.nodes_covering(x, nb);
        const int n = static_cast<int>(nb.size());
        std::vector<double> phi(n), pp(n), pm(n);
        std::vector<Vec2> dphi(n);
        REQUIRE(kernels::evaluate_shape(s, view, x, nb.data(), n, phi.data(), dphi.data()));
        const double eps = 1e-6;
        double worst = 0.0, scale = 0.0;
        for (int dir = 0; dir < 2; ++dir) {
          const Vec2 dx = dir == 0 ? Vec2(eps, 0.0) : Vec2(0.0, eps);
          REQUIRE(kernels::evaluate_shape(s, view, x + dx, nb.data(), n, pp.data(), nullptr));
          REQUIRE(kernels::evaluate_shape(s, view, x - dx, nb.data(), n, pm.data(), nullptr));
          for (int k = 0; k < n; ++k) {
            worst = std::max(worst, std::abs((pp[k] - pm[k]) / (2 * eps) - dphi[k](dir)));
            scale = std::max(scale, std::abs(dphi[k](dir)));
          }
        }
        INFO("approx " << int(approx) << " window " << int(window) << " support " << int(support));
        CHECK(worst < 1e-6 * scale);
      }
}

TEST_CASE("too few nodes in a support is reported with the point", "[kernels]") {
  const implicit::MeshfreeSpace space(lattice(2, 5),
                                      settings(Approximation::ReproducingKernel, Basis::Quadratic,
                                               WindowType::CubicSpline, SupportShape::Circular, 2),
                                      Vec2(1.1, 1.1));
  const std::vector<Vec2> pts{{0.5, 0.5}};
  CHECK_THROWS_WITH(space.shape_table(pts, {0}, space.support_lists(pts), true),
                    Catch::Contains("shape functions are undefined at (0.5, 0.5)"));
}
