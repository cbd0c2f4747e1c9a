// Drucker-Prager plasticity as pure functions: proportional (oedometric and triaxial) strain
// paths against the closed-form elastoplastic response, the apex and the tension cut-off against
// their closed forms, the algorithmic tangent against a finite-difference tangent in every
// region of the return, Mohr-Coulomb's plane-strain limit state reached by the plane-strain
// match, and the plane-stress local iteration; and the model chosen by name in a problem file.
#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <yaml-cpp/yaml.h>

using namespace mf;
using namespace mf::materials;

namespace {

constexpr double kDeg = M_PI / 180.0;

/// A dense sand-like soil (kPa): E = 30 MPa, nu = 0.3, c = 10 kPa, phi = 30 degrees.
DruckerPragerParameters soil(double psi_degrees = 30.0, double H = 0.0,
                             MohrCoulombMatch match = MohrCoulombMatch::PlaneStrain) {
  DruckerPragerParameters p;
  p.E = 30000.0;
  p.nu = 0.3;
  p.cohesion = 10.0;
  p.hardening = H;
  const ConeConstants cone = mohr_coulomb_cone(30.0 * kDeg, match);
  p.eta = cone.eta;
  p.xi = cone.xi;
  p.eta_bar = mohr_coulomb_cone(psi_degrees * kDeg, match).eta;
  return p;
}

Mat6 elastic_matrix_3d(const DruckerPragerParameters& p) {
  const double G = p.E / (2.0 * (1.0 + p.nu)), K = p.E / (3.0 * (1.0 - 2.0 * p.nu));
  const Vec6 m = voigt::unit_trace();
  return 2.0 * G * voigt::deviatoric_projector() + K * m * m.transpose();
}

/// The closed-form response to the proportional strain path eps = t d: elastic up to t_y, where
/// the cone is reached, then sigma_y + D_ep (t - t_y) d with the continuum elastoplastic modulus
/// D_ep = C - (C g)(f^T C) / (f^T C g + xi^2 H), f and g the gradients of the cone and of the
/// flow potential (engineering Voigt) at the fixed deviatoric direction of the path.
Vec6 closed_form_stress(const DruckerPragerParameters& p, const Vec6& d, double t) {
  const Mat6 C = elastic_matrix_3d(p);
  const Vec6 sd = C * d; // stress per unit t
  const Vec6 dev = voigt::deviator(sd);
  const double J = voigt::tensor_norm(dev) / std::sqrt(2.0), pm = sd.head<3>().sum() / 3.0;
  const double ty = p.xi * p.cohesion / (J + p.eta * pm);
  if (t <= ty) return t * sd;
  const Vec6 n = dev / voigt::tensor_norm(dev);
  const Vec6 m = voigt::unit_trace();
  const Vec6 f = voigt::engineering(n) / std::sqrt(2.0) + p.eta / 3.0 * m;
  const Vec6 g = voigt::engineering(n) / std::sqrt(2.0) + p.eta_bar / 3.0 * m;
  const Mat6 Dep = C - (C * g) * (f.transpose() * C) / (f.dot(C * g) + p.xi * p.xi * p.hardening);
  const Vec6 s = ty * sd + Dep * ((t - ty) * d);
  REQUIRE(voigt::deviator(s).dot(n) > 0.0); // still on the cone, not past its apex
  return s;
}

/// The update driven along eps = t d through the given values of t.
Vec6 update_along(const DruckerPragerParameters& p, const Vec6& d, const std::vector<double>& ts,
                  MaterialState* state = nullptr) {
  MaterialState h;
  StressUpdate3D r;
  for (double t : ts) {
    r = drucker_prager_update_3d(p, t * d, h);
    h = r.state;
  }
  if (state) *state = h;
  return r.stress;
}

double relative(const Vec6& a, const Vec6& b) {
  return (a - b).norm() / b.norm();
}

/// The finite-difference tangent of the update at strain e from history h (central, step 1e-7
/// of the strain's size).
Mat6 fd_tangent(const DruckerPragerParameters& p, const Vec6& e, const MaterialState& h) {
  const double step = 1e-7 * std::max(e.cwiseAbs().maxCoeff(), 1e-4);
  Mat6 D;
  for (int b = 0; b < 6; ++b) {
    Vec6 ep = e, em = e;
    ep(b) += step;
    em(b) -= step;
    D.col(b) =
        (drucker_prager_update_3d(p, ep, h).stress - drucker_prager_update_3d(p, em, h).stress) /
        (2.0 * step);
  }
  return D;
}

} // namespace

TEST_CASE("Drucker-Prager: oedometric and triaxial strain paths equal their closed forms",
          "[materials][drucker_prager]") {
  Vec6 oedometric = Vec6::Zero(), triaxial = Vec6::Zero(), shear = Vec6::Zero();
  oedometric(0) = -1.0; // compression along x, the other strains held
  triaxial << -1.0, 0.2, 0.2, 0.0, 0.0, 0.0;
  shear << 0.2, -0.15, -0.1, 0.3, 0.0, 0.8; // shear with extension along x
  const std::vector<double> steps{1e-4, 7e-4, 1.3e-3, 2.9e-3, 4e-3, 6.5e-3, 1e-2};
  for (double psi : {30.0, 10.0, 0.0})
    for (double H : {0.0, 2000.0})
      for (const Vec6& d : {oedometric, triaxial, shear}) {
        const DruckerPragerParameters p = soil(psi, H);
        MaterialState h;
        const Vec6 s = update_along(p, d, steps, &h);
        const Vec6 exact = closed_form_stress(p, d, steps.back());
        INFO("psi " << psi << " H " << H << " d " << d.transpose() << "\n  stress " << s.transpose()
                    << "\n  exact  " << exact.transpose());
        CHECK(relative(s, exact) < 1e-8);
        CHECK(h.alpha > 0.0); // every path reached the cone
        CHECK(std::abs(drucker_prager_yield(p, s, h.alpha)) < 1e-9 * p.cohesion);
        // One step to the end gives the same state: the path is proportional.
        CHECK(relative(update_along(p, d, {steps.back()}), exact) < 1e-8);
      }
}

TEST_CASE("Drucker-Prager: hydrostatic tension reaches the apex, or the tension cut-off",
          "[materials][drucker_prager]") {
  Vec6 d = Vec6::Zero();
  d.head<3>().setOnes(); // eps_v = 3 t
  const double t = 2e-3;
  for (double H : {0.0, 2000.0}) {
    const DruckerPragerParameters p = soil(20.0, H);
    const double K = p.E / (3.0 * (1.0 - 2.0 * p.nu));
    // Apex: p = (xi / eta) c(alpha), alpha = (xi / eta_bar) eps_v^p, eps_v = p / K + eps_v^p.
    const double a = p.xi / p.eta_bar, b = p.xi / p.eta;
    const double apex = b * (p.cohesion + H * a * 3.0 * t) / (1.0 + b * H * a / K);
    MaterialState h;
    const Vec6 s = update_along(p, d, {1e-4, 5e-4, t}, &h);
    INFO("H " << H << " stress " << s.transpose() << " apex " << apex);
    CHECK(std::abs(s(0) - apex) < 1e-10 * apex);
    CHECK(s.tail<3>().norm() == 0.0);
    CHECK(std::abs(s(1) - s(0)) < 1e-12 * apex);
    CHECK(std::abs(h.alpha - a * (3.0 * t - apex / K)) < 1e-10 * h.alpha);

    DruckerPragerParameters cut = p;
    cut.tension_cutoff = 0.25 * apex_pressure(p, p.cohesion);
    const Vec6 sc = update_along(cut, d, {1e-4, 5e-4, t}, &h);
    CHECK(std::abs(sc(0) - cut.tension_cutoff) < 1e-12 * cut.tension_cutoff);
    CHECK(h.alpha == 0.0); // the cut-off does not harden the cone
    CHECK(std::abs(h.plastic_strain.head<3>().sum() - (3.0 * t - cut.tension_cutoff / K)) <
          1e-12 * 3.0 * t);
  }
}

TEST_CASE("Drucker-Prager: tension with shear follows the corner's closed form",
          "[materials][drucker_prager]") {
  // eps = t (10, 10, 10, 0, 0, 1) 1e-3: the hydrostatic tension holds p on the cut-off T (the
  // cone's return alone would leave p above it), and the shear gamma_xy runs on the cone's circle
  // on the cut-off once sqrt(J2) = |s_xy| reaches xi c0 - eta T. There s_xy = G (gamma - gamma_p),
  // gamma_p = alpha / xi and s_xy = xi (c0 + H alpha) - eta T, so that
  //   alpha = (G gamma - xi c0 + eta T) / (G / xi + xi H),
  // whatever the dilatancy.
  for (double psi : {0.0, 30.0})
    for (double H : {0.0, 2000.0}) {
      DruckerPragerParameters p = soil(psi, H);
      p.tension_cutoff = 0.4 * apex_pressure(p, p.cohesion);
      const double G = p.E / (2.0 * (1.0 + p.nu));
      Vec6 d = Vec6::Zero();
      d << 1e-2, 1e-2, 1e-2, 0.0, 0.0, 1e-3;
      MaterialState h;
      const Vec6 s = update_along(p, d, {0.1, 0.2, 0.5, 1.0, 3.0}, &h);
      const double gamma = 3.0 * d(5);
      const double alpha =
          (G * gamma - p.xi * p.cohesion + p.eta * p.tension_cutoff) / (G / p.xi + p.xi * H);
      INFO("psi " << psi << " H " << H << " stress " << s.transpose() << " alpha " << h.alpha
                  << " vs " << alpha);
      CHECK(std::abs(h.alpha - alpha) < 1e-10 * alpha);
      CHECK(std::abs(s(5) - (p.xi * (p.cohesion + H * alpha) - p.eta * p.tension_cutoff)) <
            1e-10 * s(5));
      CHECK(std::abs(s.head<3>().sum() / 3.0 - p.tension_cutoff) < 1e-12 * p.tension_cutoff);
    }
}

TEST_CASE("Drucker-Prager: the algorithmic tangent equals the finite-difference tangent in every "
          "region of the return",
          "[materials][drucker_prager]") {
  struct Case {
    std::string region;
    Vec6 strain;
    bool cutoff;
  };
  Vec6 e_elastic, e_cone, e_apex, e_cutoff, e_corner;
  e_elastic << -1e-4, 2e-5, 0.0, 1e-5, 0.0, 3e-5;
  e_cone << -2e-3, 4e-4, 1e-4, 6e-4, -3e-4, 1e-3;
  e_apex << 2e-3, 2.1e-3, 1.9e-3, 1e-5, 0.0, -2e-5;
  e_cutoff << 1e-3, 1e-3, 1e-3, 1e-5, 0.0, 2e-5;
  e_corner << 1e-3, 1e-3, 1e-3, 2e-4, 0.0, 2e-3;
  const std::vector<Case> cases{{"elastic", e_elastic, false},
                                {"cone", e_cone, false},
                                {"apex", e_apex, false},
                                {"cut-off", e_cutoff, true},
                                {"corner", e_corner, true}};
  for (double psi : {30.0, 15.0})
    for (double H : {0.0, 2000.0})
      for (const Case& c : cases) {
        DruckerPragerParameters p = soil(psi, H);
        if (c.cutoff) p.tension_cutoff = 0.3 * apex_pressure(p, p.cohesion);
        MaterialState h;
        h.plastic_strain << 1e-5, -2e-5, 0.0, 0.0, 1e-5, 0.0; // a committed history too
        h.alpha = 1e-4;
        const StressUpdate3D r = drucker_prager_update_3d(p, c.strain, h);
        if (c.region == "apex" && H == 0.0) continue; // D = 0 there: nothing to compare
        const Mat6 fd = fd_tangent(p, c.strain, h);
        INFO(c.region << " psi " << psi << " H " << H << "\nalgorithmic\n"
                      << r.tangent << "\nfinite difference\n"
                      << fd);
        CHECK(r.plastic == (c.region != "elastic"));
        CHECK((r.tangent - fd).norm() < 1e-6 * fd.norm());
      }
}

TEST_CASE("Drucker-Prager's plane-strain match reaches Mohr-Coulomb's limit state in plane strain",
          "[materials][drucker_prager]") {
  // Under plane strain and associated flow, a limit state of the matched cone (stress rate zero:
  // the strain rate is all plastic and has no zz part) lies on Mohr-Coulomb's surface in the
  // plane, (s1 - s3) / 2 + (s1 + s3) / 2 sin(phi) = c cos(phi), s1 >= s3 the in-plane principal
  // stresses (de Souza Neto et al. 2008, section 6.4). The in-plane strain rate that such a
  // state admits: the unit normal n has n_zz = -sqrt2 eta / 3 (no zz flow), n_xy = 0 and
  // n_xx - n_yy = -d, d = sqrt(2 (1 - eta^2 / 3)); per unit multiplier
  //   eps_xx + eps_yy = eta,  eps_xx - eps_yy = -d / sqrt 2.
  for (double phi_deg : {0.0, 20.0, 35.0}) {
    DruckerPragerParameters p = soil();
    const ConeConstants cone = mohr_coulomb_cone(phi_deg * kDeg, MohrCoulombMatch::PlaneStrain);
    p.eta = p.eta_bar = cone.eta;
    p.xi = cone.xi;
    const double d = std::sqrt(2.0 * (1.0 - p.eta * p.eta / 3.0));
    const Vec3 rate(0.5 * (p.eta - d / std::sqrt(2.0)), 0.5 * (p.eta + d / std::sqrt(2.0)), 0.0);
    MaterialState h;
    Vec3 s;
    for (int k = 1; k <= 400; ++k) {
      const StressUpdate2D r = stress_update_plane(p, PlaneModel::PlaneStrain, 1e-4 * k * rate, h);
      h = r.state;
      s = r.stress;
    }
    const double centre = 0.5 * (s(0) + s(1));
    const double radius = std::hypot(0.5 * (s(0) - s(1)), s(2));
    const double phi = phi_deg * kDeg;
    const double mc = radius + centre * std::sin(phi) - p.cohesion * std::cos(phi);
    INFO("phi " << phi_deg << " stress " << s.transpose() << " Mohr-Coulomb residual " << mc);
    CHECK(std::abs(mc) < 1e-6 * p.cohesion);
  }
}

TEST_CASE("Drucker-Prager in plane stress: the local iteration holds szz = 0 and its condensed "
          "tangent is the derivative of the update",
          "[materials][drucker_prager]") {
  const ConstitutiveModel m = soil(20.0, 1000.0);
  MaterialState h;
  const Vec3 e(-1.5e-3, 3e-4, 8e-4);
  const StressUpdate2D r = stress_update_plane(m, PlaneModel::PlaneStress, e, h);
  REQUIRE(r.plastic);
  const StressUpdate3D r3 = stress_update_3d(m, voigt::embed(e, r.strain_zz), h);
  CHECK(std::abs(r3.stress(2)) < 1e-12 * r3.stress.norm());
  CHECK((r.stress - Vec3(r3.stress(0), r3.stress(1), r3.stress(5))).norm() == 0.0);
  Mat3 fd;
  for (int b = 0; b < 3; ++b) {
    Vec3 ep = e, em = e;
    ep(b) += 1e-10;
    em(b) -= 1e-10;
    fd.col(b) = (stress_update_plane(m, PlaneModel::PlaneStress, ep, h).stress -
                 stress_update_plane(m, PlaneModel::PlaneStress, em, h).stress) /
                2e-10;
  }
  INFO("algorithmic\n" << r.tangent << "\nfinite difference\n" << fd);
  CHECK((r.tangent - fd).norm() < 1e-5 * fd.norm());
}

TEST_CASE("Drucker-Prager: the cone constants of each Mohr-Coulomb match",
          "[materials][drucker_prager]") {
  // phi = 0: every match is the von Mises cylinder sqrt(J2) = c (plane strain, Tresca's k = c)
  // or sqrt(J2) = 2 c / sqrt 3 (the outer and inner cones through Tresca's corners at phi = 0).
  CHECK(mohr_coulomb_cone(0.0, MohrCoulombMatch::PlaneStrain).eta == 0.0);
  CHECK(mohr_coulomb_cone(0.0, MohrCoulombMatch::PlaneStrain).xi == 1.0);
  CHECK(std::abs(mohr_coulomb_cone(0.0, MohrCoulombMatch::Outer).xi - 2.0 / std::sqrt(3.0)) <
        1e-15);
  // The outer cone touches Mohr-Coulomb on its compressive meridian (triaxial compression,
  // s1 = s2 > s3).
  const double phi = 30.0 * kDeg, c = 10.0;
  const ConeConstants outer = mohr_coulomb_cone(phi, MohrCoulombMatch::Outer);
  // Triaxial compression from a mean stress p0: s = p0 + (q/3, q/3, -2q/3); sqrt(J2) = q / sqrt 3.
  // Mohr-Coulomb: (s1 - s3) / 2 + (s1 + s3) / 2 sin(phi) = c cos(phi) with s1 - s3 = q,
  // (s1 + s3) / 2 = p0 - q / 6.
  const double p0 = -20.0;
  const double q = (c * std::cos(phi) - p0 * std::sin(phi)) / (0.5 - std::sin(phi) / 6.0);
  CHECK(std::abs(q / std::sqrt(3.0) + outer.eta * p0 - outer.xi * c) < 1e-12 * c);
}

TEST_CASE("a material's plasticity chooses its model by name", "[materials][drucker_prager]") {
  const std::string soil_yaml = R"(
name: t
analysis: elastoplastic_static
model: {type: plane_strain}
materials:
  - {name: soil, E: 3.0e7, nu: 0.3,
     plasticity: {model: drucker_prager, cohesion: 1.0e4, friction_angle: 30,
                  dilation_angle: 10, tension_cutoff: 5.0e3}}
geometry: {rectangle: {origin: [0, 0], size: [1, 1]}}
discretisation: {spacing: 0.25}
boundary:
  - {name: base, edges: bottom, displacement: {x: 0, y: 0}}
  - {name: top, edges: top, displacement: {y: -1}}
steps: [{name: s, load_factor: 0.001, increments: 2}]
)";
  const spec::ProblemSpec s = spec::parse_problem(YAML::Load(soil_yaml));
  const auto& dp = std::get<DruckerPragerParameters>(*s.plasticity());
  const ConeConstants cone = mohr_coulomb_cone(30.0 * kDeg, MohrCoulombMatch::PlaneStrain);
  CHECK(dp.eta == cone.eta);
  CHECK(dp.xi == cone.xi);
  CHECK(dp.eta_bar == mohr_coulomb_cone(10.0 * kDeg, MohrCoulombMatch::PlaneStrain).eta);
  CHECK(dp.E == 3.0e7);
  CHECK(dp.tension_cutoff == 5.0e3);
  CHECK(model_name(*s.plasticity()) == "drucker_prager");
}

TEST_CASE("the SPH strength of a Drucker-Prager material is the Galerkin solvers' cone",
          "[materials][drucker_prager][sph]") {
  // A deviator of von Mises stress Y(p, alpha) at pressure p (compression positive) lies on the
  // cone of the implicit update: Phi = 0. Beyond the apex Y = 0.
  DruckerPragerParameters p = soil(10.0, 2000.0, MohrCoulombMatch::Outer);
  const DruckerPragerShear sph{p.E / (2.0 * (1.0 + p.nu)), p};
  Vec6 direction;
  direction << 0.3, -0.5, 0.2, 0.1, -0.4, 0.25;
  direction = voigt::deviator(direction);
  for (double pressure : {0.0, 5.0, 40.0, 300.0})
    for (double alpha : {0.0, 1e-3}) {
      const double Y = current_yield(StrengthModel(sph), pressure, alpha, 0.0, 0.0);
      const Vec6 stress =
          direction * (Y / von_mises_3d(direction)) - pressure * voigt::unit_trace();
      INFO("pressure " << pressure << " alpha " << alpha << " Y " << Y);
      CHECK(std::abs(drucker_prager_yield(p, stress, alpha)) < 1e-12 * (Y + p.cohesion));
    }
  const double beyond_apex = -2.0 * apex_pressure(p, p.cohesion);
  CHECK(current_yield(StrengthModel(sph), beyond_apex, 0.0, 0.0, 0.0) == 0.0);
}

TEST_CASE("SPH's deviatoric return on a Drucker-Prager cone is the Galerkin return without "
          "dilatancy, its hardening variable in the same measure",
          "[materials][drucker_prager][sph]") {
  // Without dilatancy the Galerkin return leaves p and shrinks the deviator radially, as SPH's
  // return at the equation of state's pressure does: the same deviator and the same alpha
  // (alpha' = xi dgamma), so a preload's alpha goes on in its own measure in an SPH stage.
  const DruckerPragerParameters p = soil(0.0, 0.0);
  const double G = p.E / (2.0 * (1.0 + p.nu));
  const DruckerPragerShear sph{G, p};
  Vec6 e;
  e << -2e-3, 4e-4, 1e-4, 6e-4, -3e-4, 1e-3;
  const StressUpdate3D r = drucker_prager_update_3d(p, e, MaterialState{});
  REQUIRE(r.plastic);
  const Vec6 trial = 2.0 * G * (voigt::deviatoric_projector() * e);
  const double pressure = -r.stress.head<3>().sum() / 3.0; // unchanged by the return
  const double q = von_mises_3d(trial);
  const YieldReturn ret =
      perfectly_plastic_return(q, current_yield(StrengthModel(sph), pressure, 0.0, 0.0, 0.0), G);
  REQUIRE(ret.plastic);
  CHECK((ret.scale * trial - voigt::deviator(r.stress)).norm() < 1e-12 * trial.norm());
  CHECK(std::abs(alpha_increment(sph, ret) - r.state.alpha) < 1e-12 * r.state.alpha);
}
