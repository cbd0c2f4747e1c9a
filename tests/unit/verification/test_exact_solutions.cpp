// The closed-form references are checked against themselves: the stress they give must be
// C times the symmetric gradient of the displacement they give, and in equilibrium.
#include "meshfree/verification/exact_solutions.hpp"
#include <catch2/catch.hpp>

using namespace mf;

namespace {
void check_consistent(const verification::ExactSolution& s, const materials::IsotropicElastic& m,
                      const std::vector<Vec2>& points) {
  const Mat3 C = materials::elastic_matrix(m, materials::PlaneModel::PlaneStress);
  const double h = 1e-5;
  for (const Vec2& x : points) {
    const Vec2 dx = (verification::exact_displacement(s, m, x + Vec2(h, 0)) -
                     verification::exact_displacement(s, m, x - Vec2(h, 0))) /
                    (2 * h);
    const Vec2 dy = (verification::exact_displacement(s, m, x + Vec2(0, h)) -
                     verification::exact_displacement(s, m, x - Vec2(0, h))) /
                    (2 * h);
    const Vec3 sigma = verification::exact_stress(s, m, x);
    const Vec3 from_u = C * Vec3(dx.x(), dy.y(), dx.y() + dy.x());
    CHECK((from_u - sigma).norm() < 1e-6 * sigma.norm() + 1e-9);
    // div sigma = 0
    const Vec3 sxp = verification::exact_stress(s, m, x + Vec2(h, 0)),
               sxm = verification::exact_stress(s, m, x - Vec2(h, 0));
    const Vec3 syp = verification::exact_stress(s, m, x + Vec2(0, h)),
               sym = verification::exact_stress(s, m, x - Vec2(0, h));
    const double fx = (sxp(0) - sxm(0) + syp(2) - sym(2)) / (2 * h);
    const double fy = (sxp(2) - sxm(2) + syp(1) - sym(1)) / (2 * h);
    CHECK(std::hypot(fx, fy) < 1e-5 * (sigma.norm() + 1.0));
  }
}
} // namespace

TEST_CASE("Timoshenko beam: stress is C grad u, equilibrium holds, end shear resultant is P",
          "[exact]") {
  const verification::TimoshenkoBeam b{1000.0, 48.0, 12.0};
  const materials::IsotropicElastic m{3e7, 0.3};
  check_consistent(b, m, {{1.0, 2.0}, {24.0, -5.0}, {40.0, 0.3}});
  double shear = 0.0; // Simpson on the end section
  const int n = 200;
  for (int k = 0; k <= n; ++k) {
    const double y = -6.0 + 12.0 * k / n, w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    shear += w * verification::exact_stress(b, m, {48.0, y})(2) * 12.0 / n / 3.0;
  }
  CHECK(shear == Approx(1000.0).epsilon(1e-10));
}

TEST_CASE("Kirsch plate: consistency, traction-free hole, 3 sigma0 at the hole's top", "[exact]") {
  const verification::KirschPlate k{1.0, 100.0};
  const materials::IsotropicElastic m{2.1e5, 0.3};
  check_consistent(k, m, {{0.3, 1.2}, {2.0, 3.0}, {1.5, 0.2}});
  for (double th : {0.1, 0.7, 1.3}) { // sigma . n = 0 on r = a
    const Vec2 n(std::cos(th), std::sin(th));
    const Vec3 s = verification::exact_stress(k, m, n);
    CHECK(std::hypot(s(0) * n.x() + s(2) * n.y(), s(2) * n.x() + s(1) * n.y()) < 1e-12);
  }
  CHECK(verification::exact_stress(k, m, {0.0, 1.0})(0) == Approx(300.0).epsilon(1e-12));
}
