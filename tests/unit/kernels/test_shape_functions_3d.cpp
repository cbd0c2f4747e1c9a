// 3D reproducing kernels: complete polynomials of the basis reproduced to round-off at every
// point of a box (faces, edges and corners included) from a jittered lattice, for spherical and
// box supports; gradients against central differences; too few nodes refused.
#include "meshfree/implicit/solid_space.hpp"
#include <catch2/catch.hpp>
#include <functional>

using namespace mf;
using kernels::Basis;
using kernels::SupportShape;

namespace {

implicit::SolidNodes lattice(int n, double jitter) {
  implicit::SolidNodes c;
  const double h = 1.0 / (n - 1);
  unsigned seed = 2024;
  auto rnd = [&]() { // deterministic LCG in [-0.5, 0.5)
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec3 p(i * h, j * h, k * h);
        const bool interior = i > 0 && i < n - 1 && j > 0 && j < n - 1 && k > 0 && k < n - 1;
        if (interior) p += jitter * h * Vec3(rnd(), rnd(), rnd());
        c.x.push_back(p);
        c.spacing.push_back(h);
        c.volume.push_back(h * h * h);
      }
  return c;
}

std::vector<Vec3> samples() {
  std::vector<Vec3> pts;
  const int m = 9;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) pts.emplace_back(i / (m - 1.0), j / (m - 1.0), k / (m - 1.0));
  return pts;
}

struct Errors {
  double value = 0.0, gradient = 0.0;
};

Errors reproduction(const implicit::SolidSpace& space, const std::function<double(const Vec3&)>& f,
                    const std::function<Vec3(const Vec3&)>& grad) {
  const auto pts = samples();
  std::vector<int> rows(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) rows[i] = static_cast<int>(i);
  const auto t = space.shape_table(pts, rows, space.support_lists(pts), true);
  Errors e;
  for (int r = 0; r < t.rows(); ++r) {
    double v = 0.0;
    Vec3 g = Vec3::Zero();
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
      const double fi = f(space.nodes().x[t.node[k]]);
      v += t.phi[k] * fi;
      g += t.dphi[k] * fi;
    }
    e.value = std::max(e.value, std::abs(v - f(pts[r])));
    e.gradient = std::max(e.gradient, (g - grad(pts[r])).cwiseAbs().maxCoeff());
  }
  return e;
}

kernels::ShapeSettings settings(Basis b, SupportShape s) {
  kernels::ShapeSettings k;
  k.basis = b;
  k.support = s;
  k.dim = 3;
  return k;
}

} // namespace

TEST_CASE("3D RK shape functions reproduce their basis at every point of a box",
          "[kernels][solid3d]") {
  for (const SupportShape shape : {SupportShape::Circular, SupportShape::Rectangular}) {
    for (const Basis basis : {Basis::Linear, Basis::Quadratic}) {
      const double dilation = basis == Basis::Quadratic ? 3.0 : 2.0;
      const implicit::SolidSpace space(lattice(7, 0.3), settings(basis, shape), dilation);
      INFO("support " << (shape == SupportShape::Circular ? "spherical" : "box") << ", basis "
                      << (basis == Basis::Quadratic ? "quadratic" : "linear"));
      const Errors one = reproduction(
          space, [](const Vec3&) { return 1.0; }, [](const Vec3&) { return Vec3::Zero().eval(); });
      CHECK(one.value < 1e-12);
      CHECK(one.gradient < 1e-10);
      const Errors lin = reproduction(
          space, [](const Vec3& x) { return 0.3 - 1.2 * x.x() + 0.7 * x.y() + 2.1 * x.z(); },
          [](const Vec3&) { return Vec3(-1.2, 0.7, 2.1); });
      CHECK(lin.value < 1e-12);
      CHECK(lin.gradient < 1e-10);
      const auto quad = [](const Vec3& x) {
        return x.x() * x.x() - 2.0 * x.y() * x.z() + 0.5 * x.z() * x.z() + x.x() * x.y();
      };
      const auto quad_grad = [](const Vec3& x) {
        return Vec3(2.0 * x.x() + x.y(), -2.0 * x.z() + x.x(), -2.0 * x.y() + x.z());
      };
      const Errors q = reproduction(space, quad, quad_grad);
      if (basis == Basis::Quadratic) {
        CHECK(q.value < 1e-11);
        CHECK(q.gradient < 1e-9);
      } else {
        CHECK(q.value > 1e-4); // a linear basis cannot reproduce it: the check can fail
      }
    }
  }
}

TEST_CASE("3D RK gradients equal central differences of the shape functions",
          "[kernels][solid3d]") {
  const implicit::SolidSpace space(lattice(6, 0.25),
                                   settings(Basis::Linear, SupportShape::Circular), 2.0);
  const Vec3 x(0.37, 0.52, 0.21);
  std::vector<int> support;
  space.nodes_covering(x, support);
  REQUIRE(support.size() >= 4);
  const int n = static_cast<int>(support.size());
  std::vector<double> phi(n), plus(n), minus(n);
  std::vector<Vec3> grad(n);
  REQUIRE(kernels::evaluate_shape_3d(settings(Basis::Linear, SupportShape::Circular), space.view(),
                                     x, support.data(), n, phi.data(), grad.data()));
  const double eps = 1e-6;
  double worst = 0.0, largest = 0.0;
  for (int c = 0; c < 3; ++c) {
    Vec3 dx = Vec3::Zero();
    dx(c) = eps;
    // the same node list on both sides: no node's support edge lies within eps of x here
    REQUIRE(kernels::evaluate_shape_3d(settings(Basis::Linear, SupportShape::Circular),
                                       space.view(), x + dx, support.data(), n, plus.data(),
                                       nullptr));
    REQUIRE(kernels::evaluate_shape_3d(settings(Basis::Linear, SupportShape::Circular),
                                       space.view(), x - dx, support.data(), n, minus.data(),
                                       nullptr));
    for (int k = 0; k < n; ++k) {
      worst = std::max(worst, std::abs((plus[k] - minus[k]) / (2.0 * eps) - grad[k](c)));
      largest = std::max(largest, std::abs(grad[k](c)));
    }
  }
  CHECK(worst < 1e-7 * largest);
}

TEST_CASE("3D RK refuses points covered by nodes in one plane", "[kernels][solid3d]") {
  implicit::SolidNodes plane;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      plane.x.emplace_back(i * 0.5, j * 0.5, 0.0);
      plane.spacing.push_back(0.5);
      plane.volume.push_back(0.125);
    }
  const implicit::SolidSpace space(plane, settings(Basis::Linear, SupportShape::Circular), 2.0);
  const std::vector<Vec3> x{Vec3(0.5, 0.5, 0.1)};
  CHECK_THROWS_WITH(space.shape_table(x, {0}, space.support_lists(x), true),
                    Catch::Contains("in a plane for the 4-term basis"));
}
