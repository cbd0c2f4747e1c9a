// J2 plasticity as pure functions: the algorithmic tangent against a finite-difference tangent of
// the stress update, the returned stress on the yield surface, plane stress keeping szz = 0, and
// uniaxial and shear paths against their closed-form answers, for every hardening law; the
// plane-stress return against the 3D return at its eps_zz.
#include "meshfree/materials/j2_plasticity.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>
#include <random>
#include <string>

using namespace mf;
using namespace mf::materials;

namespace {

struct Law {
  std::string name;
  J2Parameters p;
};

/// Every hardening law, with steel-like constants (MPa); the last one combines Voce isotropic
/// hardening with linear kinematic hardening.
std::vector<Law> laws() {
  J2Parameters base;
  base.E = 200000.0;
  base.nu = 0.3;
  base.sigma0 = 250.0;
  std::vector<Law> out;
  out.push_back({"perfect", base});
  J2Parameters lin = base;
  lin.hardening = LinearHardening{2000.0};
  out.push_back({"linear", lin});
  J2Parameters voce = base;
  voce.hardening = VoceHardening{129.24, 400.0, 16.93};
  out.push_back({"voce", voce});
  J2Parameters swift = base;
  swift.hardening = SwiftHardening{600.0, 0.01, 0.2};
  swift.sigma0 = 600.0 * std::pow(0.01, 0.2);
  out.push_back({"swift", swift});
  J2Parameters table = base;
  table.hardening = TableHardening{{0.0, 0.01, 0.05, 0.2}, {250.0, 280.0, 330.0, 360.0}};
  out.push_back({"table", table});
  J2Parameters kin = base;
  kin.H_kinematic = 5000.0;
  out.push_back({"kinematic", kin});
  J2Parameters mixed = voce;
  mixed.H_kinematic = 3000.0;
  out.push_back({"voce+kinematic", mixed});
  return out;
}

enum class Model { ThreeD, PlaneStrain, PlaneStress };

/// A history left by a first plastic step, so that the tested step starts from nonzero plastic
/// strain, back stress and alpha.
MaterialState prestrained(const J2Parameters& p, Model m) {
  const MaterialState zero;
  if (m == Model::ThreeD) {
    Vec6 e;
    e << 3e-3, -1e-3, -0.5e-3, 0.4e-3, -0.2e-3, 1.5e-3;
    return j2_update_3d(p, e, zero).state;
  }
  const Vec3 e(3e-3, -1e-3, 1.5e-3);
  return m == Model::PlaneStrain ? j2_update_plane_strain(p, e, zero).state
                                 : j2_update_plane_stress(p, e, zero).state;
}

/// Largest entry of |C_algorithmic - C_fd| over the largest entry of C, with central differences.
template <int N, class Update>
double tangent_error(const Eigen::Matrix<double, N, 1>& strain, Update update) {
  const auto r = update(strain);
  Eigen::Matrix<double, N, N> fd;
  const double h = 1e-8;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> ep = strain, em = strain;
    ep(j) += h;
    em(j) -= h;
    fd.col(j) = (update(ep).stress - update(em).stress) / (2.0 * h);
  }
  return (r.tangent - fd).cwiseAbs().maxCoeff() / r.tangent.cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("the algorithmic tangent equals the finite-difference tangent of the stress update",
          "[materials]") {
  // Strain increments from the prestrained state: further loading (plastic), a small step
  // (elastic or just yielding) and a reversal (elastic unloading, then reverse yielding).
  const std::vector<double> scales = {1.0, 0.05, -0.3, -2.0};
  for (const Law& law : laws()) {
    for (Model m : {Model::ThreeD, Model::PlaneStrain, Model::PlaneStress}) {
      const MaterialState h = prestrained(law.p, m);
      for (double s : scales) {
        double err = 0.0;
        bool plastic = false;
        if (m == Model::ThreeD) {
          Vec6 e;
          e << 3e-3, -1e-3, -0.5e-3, 0.4e-3, -0.2e-3, 1.5e-3;
          Vec6 de;
          de << 1.2e-3, 0.3e-3, -0.6e-3, 0.2e-3, 0.5e-3, -0.4e-3;
          const Vec6 strain = e + s * de;
          err = tangent_error<6>(strain, [&](const Vec6& x) { return j2_update_3d(law.p, x, h); });
          plastic = j2_update_3d(law.p, strain, h).plastic;
        } else {
          const Vec3 strain = Vec3(3e-3, -1e-3, 1.5e-3) + s * Vec3(1.2e-3, 0.3e-3, -0.4e-3);
          const auto update = [&](const Vec3& x) {
            return m == Model::PlaneStrain ? j2_update_plane_strain(law.p, x, h)
                                           : j2_update_plane_stress(law.p, x, h);
          };
          err = tangent_error<3>(strain, update);
          plastic = update(strain).plastic;
        }
        INFO(law.name << " model " << static_cast<int>(m) << " scale " << s << " plastic "
                      << plastic << " error " << err);
        CHECK(err < 1e-6);
      }
    }
  }
}

TEST_CASE("the tested paths cover elastic and plastic steps", "[materials]") {
  const Law law = laws()[1];
  const MaterialState h = prestrained(law.p, Model::PlaneStress);
  const Vec3 e(3e-3, -1e-3, 1.5e-3), de(1.2e-3, 0.3e-3, -0.4e-3);
  CHECK(j2_update_plane_stress(law.p, e + de, h).plastic);
  CHECK_FALSE(j2_update_plane_stress(law.p, e - 0.3 * de, h).plastic);
}

TEST_CASE("a plastic step returns the stress to the yield surface", "[materials]") {
  for (const Law& law : laws()) {
    const MaterialState zero;
    Vec6 e;
    e << 5e-3, -2e-3, -1e-3, 1e-3, 0.5e-3, 2e-3;
    const StressUpdate3D r = j2_update_3d(law.p, e, zero);
    REQUIRE(r.plastic);
    Vec6 xi = r.stress - r.state.back_stress;
    xi.head<3>().array() -= r.stress.head<3>().sum() / 3.0;
    const double f = von_mises_3d(xi) - yield_stress(law.p, r.state.alpha);
    INFO(law.name << ": f = " << f);
    CHECK(std::abs(f) <= 1e-10 * yield_stress(law.p, r.state.alpha));

    const StressUpdate2D ps = j2_update_plane_stress(law.p, Vec3(5e-3, -1e-3, 3e-3), zero);
    REQUIRE(ps.plastic);
    Vec6 s3;
    s3 << ps.stress(0), ps.stress(1), ps.stress_zz, 0.0, 0.0, ps.stress(2);
    Vec6 xi2 = s3 - ps.state.back_stress;
    xi2.head<3>().array() -= s3.head<3>().sum() / 3.0;
    const double f2 = von_mises_3d(xi2) - yield_stress(law.p, ps.state.alpha);
    CHECK(std::abs(f2) <= 1e-10 * yield_stress(law.p, ps.state.alpha));
    CHECK(std::abs(ps.stress_zz) <= 1e-10 * law.p.sigma0);
  }
}

TEST_CASE("the plane-stress return is the 3D return at its eps_zz, along a path that reverses",
          "[materials]") {
  // The projected plane-stress return and the 3D radial return are two algorithms for the same
  // backward-Euler step: the 3D update at the plane-stress eps_zz must give sigma_zz = 0, the same
  // in-plane stress and the same history, and its tangent condensed on sigma_zz = 0 the same
  // plane-stress tangent. The path loads, turns and reverses, with increments large and small.
  const std::vector<Vec3> path = {{2e-3, -0.5e-3, 1e-3},     {4e-3, -1e-3, 3e-3},
                                  {4.1e-3, -0.9e-3, 3.2e-3}, {1e-3, 2e-3, 4e-3},
                                  {-3e-3, 1e-3, -2e-3},      {-6e-3, -4e-3, 1e-3}};
  for (const Law& law : laws()) {
    MaterialState ps, s3;
    int plastic_steps = 0;
    for (const Vec3& e : path) {
      const StressUpdate2D r = j2_update_plane_stress(law.p, e, ps);
      Vec6 e3;
      e3 << e(0), e(1), r.strain_zz, 0.0, 0.0, e(2);
      const StressUpdate3D q = j2_update_3d(law.p, e3, s3);
      const double scale = yield_stress(law.p, q.state.alpha);
      INFO(law.name << " at " << e.transpose() << ": sigma_zz " << q.stress(2));
      CHECK(std::abs(q.stress(2)) <= 1e-9 * scale);
      for (int a = 0; a < 3; ++a)
        CHECK(std::abs(r.stress(a) - q.stress(kPlane[a])) <= 1e-9 * scale);
      CHECK(r.plastic == q.plastic);
      CHECK(std::abs(r.state.alpha - q.state.alpha) <= 1e-12);
      CHECK((r.state.plastic_strain - q.state.plastic_strain).cwiseAbs().maxCoeff() <= 1e-12);
      CHECK((r.state.back_stress - q.state.back_stress).cwiseAbs().maxCoeff() <= 1e-9 * scale);
      Mat3 condensed;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          condensed(a, b) = q.tangent(kPlane[a], kPlane[b]) -
                            q.tangent(kPlane[a], 2) * q.tangent(2, kPlane[b]) / q.tangent(2, 2);
      CHECK((r.tangent - condensed).cwiseAbs().maxCoeff() <= 1e-9 * law.p.E);
      plastic_steps += r.plastic;
      ps = r.state;
      s3 = q.state;
    }
    CHECK(plastic_steps >= 3);
  }
}

TEST_CASE(
    "the plane-stress return holds from small strains to strains of 1e5 and nearly incompressible",
    "[materials]") {
  // One step from the virgin state to random strains of growing size (up to 8e7 times the yield
  // strain, as a first Newton iterate far from equilibrium can ask for): the scalar iteration
  // converges and agrees with the 3D return at its eps_zz.
  std::vector<Law> all = laws();
  J2Parameters incompressible = all[2].p;
  incompressible.nu = 0.4999;
  all.push_back({"voce, nu 0.4999", incompressible});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Law& law : all)
    for (double size : {1e-3, 1e-2, 0.1, 1.0, 10.0, 1e3, 1e5})
      for (int i = 0; i < 40; ++i) {
        const Vec3 e = size * Vec3(u(rng), u(rng), u(rng));
        const StressUpdate2D r = j2_update_plane_stress(law.p, e, MaterialState{});
        Vec6 e3;
        e3 << e(0), e(1), r.strain_zz, 0.0, 0.0, e(2);
        const StressUpdate3D q = j2_update_3d(law.p, e3, MaterialState{});
        const double scale = yield_stress(law.p, q.state.alpha);
        INFO(law.name << " at " << e.transpose());
        CHECK(std::abs(q.stress(2)) <= 1e-7 * scale);
        for (int a = 0; a < 3; ++a)
          CHECK(std::abs(r.stress(a) - q.stress(kPlane[a])) <= 1e-7 * scale);
      }
}

namespace {

/// Uniaxial stress in x under plane stress: eps_yy is found by Newton (with the algorithmic
/// tangent) so that syy = 0; sxy = 0 by symmetry. Returns sxx and updates the history.
double uniaxial_step(const J2Parameters& p, double exx, double& eyy, MaterialState& state) {
  StressUpdate2D r;
  for (int it = 0; it < 30; ++it) {
    r = j2_update_plane_stress(p, Vec3(exx, eyy, 0.0), state);
    if (std::abs(r.stress(1)) < 1e-11 * p.sigma0) break;
    eyy -= r.stress(1) / r.tangent(1, 1);
  }
  REQUIRE(std::abs(r.stress(1)) < 1e-9 * p.sigma0);
  state = r.state;
  return r.stress(0);
}

} // namespace

TEST_CASE("uniaxial stress paths follow the closed-form hardening curves", "[materials]") {
  // Monotonic uniaxial loading: sxx = sigma_y(alpha) + Hk alpha with the axial plastic strain
  // equal to alpha (J2 with isochoric flow), so eps = sxx / E + alpha.
  for (const Law& law : laws()) {
    MaterialState state;
    double eyy = 0.0, worst = 0.0;
    const double ey = law.p.sigma0 / law.p.E;
    for (int k = 1; k <= 60; ++k) {
      const double exx = ey * 0.25 * k; // up to 15 times the yield strain
      const double s = uniaxial_step(law.p, exx, eyy, state);
      const double alpha = state.alpha;
      const double expected =
          alpha > 0.0 ? yield_stress(law.p, alpha) + law.p.H_kinematic * alpha : law.p.E * exx;
      worst = std::max(worst, std::abs(s - expected) / law.p.sigma0);
      if (alpha > 0.0) CHECK(std::abs(exx - s / law.p.E - alpha) < 1e-12);
      if (exx < ey * (1.0 - 1e-9)) CHECK(alpha == 0.0);
    }
    INFO(law.name << ": worst relative stress error " << worst);
    CHECK(worst < 1e-10);
  }
}

TEST_CASE("linear hardening: tangent modulus E H / (E + H) and the Bauschinger effect",
          "[materials]") {
  const double E = 200000.0, s0 = 250.0, H = 2000.0;
  for (bool kinematic : {false, true}) {
    J2Parameters p;
    p.E = E;
    p.nu = 0.3;
    p.sigma0 = s0;
    if (kinematic)
      p.H_kinematic = H;
    else
      p.hardening = LinearHardening{H};
    MaterialState state;
    double eyy = 0.0;
    const double ey = s0 / E, e_max = 10.0 * ey;
    const double s_max = uniaxial_step(p, e_max, eyy, state);
    CHECK(s_max == Approx(s0 + E * H / (E + H) * (e_max - ey)).epsilon(1e-12));
    // Unload elastically, then load in compression until reverse yielding: kinematic hardening
    // yields again at s_max - 2 s0, isotropic hardening at -s_max.
    const double reverse_yield = kinematic ? s_max - 2.0 * s0 : -s_max;
    const double e_reverse = e_max - (s_max - reverse_yield) / E;
    MaterialState s1 = state;
    double eyy1 = eyy;
    const double just_before = uniaxial_step(p, e_reverse + 1e-9, eyy1, s1);
    CHECK(s1.alpha == state.alpha);
    CHECK(just_before == Approx(reverse_yield + E * 1e-9).epsilon(1e-9));
    MaterialState s2 = state;
    double eyy2 = eyy;
    const double beyond = uniaxial_step(p, e_reverse - 10.0 * ey, eyy2, s2);
    CHECK(s2.alpha > state.alpha);
    CHECK(beyond == Approx(reverse_yield - E * H / (E + H) * 10.0 * ey).epsilon(1e-10));
  }
}

TEST_CASE("pure shear in plane stress yields at sigma_y / sqrt(3)", "[materials]") {
  J2Parameters p;
  p.E = 200000.0;
  p.nu = 0.3;
  p.sigma0 = 250.0;
  const double G = p.E / (2.0 * (1.0 + p.nu));
  const MaterialState zero;
  const double gamma_y = p.sigma0 / std::sqrt(3.0) / G;
  const StressUpdate2D below = j2_update_plane_stress(p, Vec3(0.0, 0.0, 0.999 * gamma_y), zero);
  CHECK_FALSE(below.plastic);
  CHECK(below.stress(2) == Approx(0.999 * p.sigma0 / std::sqrt(3.0)).epsilon(1e-12));
  const StressUpdate2D above = j2_update_plane_stress(p, Vec3(0.0, 0.0, 5.0 * gamma_y), zero);
  CHECK(above.plastic);
  CHECK(above.stress(2) == Approx(p.sigma0 / std::sqrt(3.0)).epsilon(1e-10));
  CHECK(std::abs(above.stress(0)) < 1e-9);
  CHECK(std::abs(above.stress_zz) < 1e-9);
}

TEST_CASE("plane strain keeps eps_zz = 0 and develops szz, and its elastic stress is Hooke's law",
          "[materials]") {
  J2Parameters p;
  p.E = 200000.0;
  p.nu = 0.3;
  p.sigma0 = 250.0;
  const MaterialState zero;
  const StressUpdate2D el = j2_update_plane_strain(p, Vec3(1e-4, -0.5e-4, 0.2e-4), zero);
  REQUIRE_FALSE(el.plastic);
  const double lam = p.E * p.nu / ((1 + p.nu) * (1 - 2 * p.nu)), G = p.E / (2 * (1 + p.nu));
  CHECK(el.stress(0) == Approx((lam + 2 * G) * 1e-4 + lam * -0.5e-4).epsilon(1e-12));
  CHECK(el.stress_zz == Approx(lam * 0.5e-4).epsilon(1e-12));
  CHECK(el.stress(2) == Approx(G * 0.2e-4).epsilon(1e-12));
  CHECK(el.strain_zz == 0.0);
  const StressUpdate2D pl = j2_update_plane_strain(p, Vec3(5e-3, -1e-3, 2e-3), zero);
  REQUIRE(pl.plastic);
  // Isochoric flow: the plastic strain has no trace.
  CHECK(std::abs(pl.state.plastic_strain.head<3>().sum()) < 1e-15);
}
