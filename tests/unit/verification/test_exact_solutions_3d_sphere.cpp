// Lame's hollow sphere (verification::ThickSphere) checked against itself and its boundary
// conditions: its stress is Hooke's law of the symmetric gradient of its displacement, in
// equilibrium (central differences), the traction is -p n on the cavity and zero on the outer
// surface, and an infinite outer radius gives the unbounded body's u_r = p a^3 / (4 G r^2).
#include "meshfree/verification/exact_solutions_3d.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using namespace mf;

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

Mat3 tensor(const Vec6& s) {
  Mat3 t;
  t << s(0), s(5), s(4), s(5), s(1), s(3), s(4), s(3), s(2);
  return t;
}

/// Hooke's law of the central-difference gradient of u, and the divergence of sigma.
void check_field(const verification::ExactSolution3D& s, const materials::IsotropicElastic& m,
                 const Vec3& x, double scale) {
  const double h = 1e-5;
  Mat3 grad;
  Vec3 divergence = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    Vec3 e = Vec3::Zero();
    e(j) = h;
    grad.col(j) = (verification::exact_displacement_3d(s, m, x + e) -
                   verification::exact_displacement_3d(s, m, x - e)) /
                  (2 * h);
    const Mat3 ds = (tensor(verification::exact_stress_3d(s, m, x + e)) -
                     tensor(verification::exact_stress_3d(s, m, x - e))) /
                    (2 * h);
    divergence += ds.col(j);
  }
  const Mat3 eps = 0.5 * (grad + grad.transpose());
  const double mu = m.E / (2 * (1 + m.nu)), lambda = m.E * m.nu / ((1 + m.nu) * (1 - 2 * m.nu));
  const Mat3 hooke = lambda * eps.trace() * Mat3::Identity() + 2 * mu * eps;
  REQUIRE((hooke - tensor(verification::exact_stress_3d(s, m, x))).norm() < 1e-6 * scale);
  REQUIRE(divergence.norm() < 1e-5 * scale);
}

} // namespace

TEST_CASE("Lame's hollow sphere: Hooke, equilibrium, the tractions on its surfaces",
          "[verification][solid3d][sphere]") {
  const materials::IsotropicElastic m{200000.0, 0.3};
  for (double b : {2.0, 5.0, std::numeric_limits<double>::infinity()}) {
    CAPTURE(b);
    const verification::ExactSolution3D s = verification::ThickSphere{1.0, b, 100.0};
    for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0.48, -0.6, 0.64), Vec3(-0.36, 0.48, 0.8)}) {
      for (double r : {1.2, 1.7}) check_field(s, m, r * dir, 100.0);
      const Vec3 t_inner = tensor(verification::exact_stress_3d(s, m, dir)) * dir;
      REQUIRE((t_inner + 100.0 * dir).norm() < 1e-10);
      if (std::isfinite(b)) {
        const Vec3 t_outer = tensor(verification::exact_stress_3d(s, m, b * dir)) * dir;
        REQUIRE(t_outer.norm() < 1e-10);
      }
    }
  }
  const verification::ExactSolution3D unbounded =
      verification::ThickSphere{1.0, std::numeric_limits<double>::infinity(), 100.0};
  const double G = 200000.0 / (2 * 1.3);
  for (double r : {1.0, 2.0, 3.5}) {
    const Vec3 u = verification::exact_displacement_3d(unbounded, m, Vec3(0, 0, r));
    CHECK(u.z() == Approx(100.0 / (4 * G * r * r)).epsilon(1e-14));
    CHECK(u.head<2>().norm() == 0.0);
  }
}
