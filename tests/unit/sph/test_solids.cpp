// SPH solids: elastic waves against one-dimensional theory, the Hugoniot elastic limit of a bar
// impact, the deviatoric J2 update against the implicit one, blast impulse on a plate, transmitting
// boundaries, artificial stress and symmetry planes.
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/loads/blast.hpp"
#include "meshfree/materials/eos.hpp"
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/sph/detonation.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
#include "meshfree/sph/step.hpp"
#include "meshfree/sph/surface_load.hpp"
#include "meshfree/sph/transmitting_boundary.hpp"
#include "sph_test_support.hpp"
#include "test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

using namespace mf;

namespace {

struct BarImpact {
  double elastic_stress = 0.0, final_stress = 0.0; // mean sigma_xx over the two plateaus
  double elastic_speed = 0.0, plastic_speed = 0.0; // of the half-level crossings, 2/3 t to t
  double energy_drift = 0.0;
};

/// Two identical bars in uniaxial strain (1D) meet at x = 0 with velocities +-v0: K = 70 GPa,
/// G = 26 GPa, rho = 2700 kg/m^3 (linear EOS p = K mu), J2 yield sigma_y (<= 0: elastic).
/// 400 particles per 50 mm bar, h = 2 dx, run to t. (On a uniform 1D lattice the SPH gradient of
/// a linear field, -2 dx sum_k k dx W'(k dx), is exactly 1 at h = 2 dx but 0.9877 at h = 1.5 dx,
/// which slows waves by 1.2%: measured 1.27% at 1.5 dx.) Front speeds come from the fronts'
/// positions at 2/3 t and t: the elastic bar's front is its disturbed length, the plastic bar's
/// fronts are the half-level crossings of the two waves.
BarImpact bar_impact(double v0, double sigma_y, double t_end, double smoothing = 2.0,
                     bool corrected = false) {
  sph::Hydro s;
  s.dim = 1;
  s.settings.gradient_correction = corrected;
  s.materials.push_back(test_solid(sigma_y));
  const int n = 400;
  const double dx = 0.05 / n;
  for (int k = 0; k < 2 * n; ++k) {
    const double x[3] = {-0.05 + (k + 0.5) * dx, 0, 0};
    add(s, x, dx, 2700.0, 0.0, smoothing * dx, 0);
    s.particles.v[3 * k] = x[0] < 0.0 ? v0 : -v0;
  }
  sph::update_state(s);
  const double e0 = sph::energies(s).total();
  const double cl = std::sqrt((70e9 + 4.0 / 3.0 * 26e9) / 2700.0), cp = std::sqrt(70e9 / 2700.0);
  BarImpact out;
  double front_e[2] = {0, 0}, front_p[2] = {0, 0}, when[2] = {2.0 / 3.0 * t_end, t_end};
  for (int stage = 0; stage < 2; ++stage) {
    const double t = when[stage];
    while (s.particles.time < t)
      sph::advance(s, std::min(sph::stable_step(s), t - s.particles.time));
    const particles::ParticleSet& P = s.particles;
    const sph::ParticleFields& F = s.fields;
    // Right half: sigma_xx = -p + S_xx against x.
    std::vector<std::pair<double, double>> prof;
    for (int i = 0; i < P.size(); ++i)
      if ((P.X[3 * i] + P.u[3 * i]) > 0.0)
        prof.emplace_back((P.X[3 * i] + P.u[3 * i]), -F.p[i] + F.S[6 * i]);
    std::sort(prof.begin(), prof.end());
    const auto mean_over = [&](double a, double b) {
      double sum = 0.0;
      int count = 0;
      for (const auto& [x, sxx] : prof)
        if (x > a && x < b) sum += sxx, ++count;
      return sum / count;
    };
    const auto crossing = [&](double level) { // the last x where sigma_xx crosses level
      double where = 0.0;
      for (std::size_t k = 0; k + 1 < prof.size(); ++k)
        if ((prof[k].second - level) * (prof[k + 1].second - level) <= 0.0)
          where = prof[k].first + (prof[k + 1].first - prof[k].first) * (prof[k].second - level) /
                                      (prof[k].second - prof[k + 1].second);
      return where;
    };
    if (sigma_y <= 0.0) {
      // The disturbed length: the integral of sigma_xx / plateau over the bar (m / rho per
      // particle), which the smearing of the front does not shift.
      out.final_stress = mean_over(0.1 * cl * t, 0.8 * cl * t);
      double length = 0.0;
      for (int i = 0; i < P.size(); ++i)
        if ((P.X[3 * i] + P.u[3 * i]) > 0.0)
          length += (-F.p[i] + F.S[6 * i]) / out.final_stress * P.mass[i] / F.rho[i];
      front_e[stage] = length;
    } else {
      out.final_stress = mean_over(0.1 * cp * t, 0.85 * cp * t);
      out.elastic_stress = mean_over(1.06 * cp * t, 0.95 * cl * t);
      front_e[stage] = crossing(0.5 * out.elastic_stress);
      front_p[stage] = crossing(0.5 * (out.elastic_stress + out.final_stress));
    }
  }
  out.elastic_speed = (front_e[1] - front_e[0]) / (when[1] - when[0]);
  out.plastic_speed = (front_p[1] - front_p[0]) / (when[1] - when[0]);
  out.energy_drift = std::abs(sph::energies(s).total() - e0) / e0;
  return out;
}

} // namespace

TEST_CASE("elastic wave in a bar: speed and stress against the one-dimensional theory",
          "[sph][solid]") {
  // Uniaxial strain: c_L = sqrt((K + 4G/3) / rho) and sigma_xx = -rho c_L v0 behind the fronts.
  const double v0 = 1.0, t = 5e-6;
  const double cl = std::sqrt((70e9 + 4.0 / 3.0 * 26e9) / 2700.0);
  const BarImpact r = bar_impact(v0, 0.0, t);
  std::printf("  elastic bar: sigma_xx %.4g MPa (theory %.4g), front speed %.0f m/s (c_L %.0f), "
              "energy drift %.2e\n",
              r.final_stress / 1e6, -2700.0 * cl * v0 / 1e6, r.elastic_speed, cl, r.energy_drift);
  CHECK(r.final_stress == Approx(-2700.0 * cl * v0).epsilon(0.01));
  CHECK(r.elastic_speed == Approx(cl).epsilon(0.005)); // measured -0.05%
  CHECK(r.energy_drift < 1e-3);
}

TEST_CASE("kernel-gradient correction removes the slow-down of waves at h = 1.5 dx",
          "[sph][solid]") {
  // Uncorrected, the SPH gradient of a linear field on the lattice is 0.9877 of the exact one at
  // h = 1.5 dx, and the wave runs 1.27% slow; the corrected gradient is exact for linear fields.
  const double v0 = 1.0, t = 5e-6;
  const double cl = std::sqrt((70e9 + 4.0 / 3.0 * 26e9) / 2700.0);
  const BarImpact plain = bar_impact(v0, 0.0, t, 1.5, false);
  const BarImpact fixed = bar_impact(v0, 0.0, t, 1.5, true);
  std::printf("  h = 1.5 dx: front speed %.2f%% (plain), %.2f%% (corrected) off c_L; stress "
              "%.2f%% / %.2f%%; energy drift %.1e / %.1e\n",
              100 * (plain.elastic_speed / cl - 1), 100 * (fixed.elastic_speed / cl - 1),
              100 * (plain.final_stress / (-2700.0 * cl * v0) - 1),
              100 * (fixed.final_stress / (-2700.0 * cl * v0) - 1), plain.energy_drift,
              fixed.energy_drift);
  CHECK(plain.elastic_speed < 0.99 * cl);
  CHECK(fixed.elastic_speed == Approx(cl).epsilon(0.003));
  CHECK(fixed.final_stress == Approx(-2700.0 * cl * v0).epsilon(0.01));
  CHECK(fixed.energy_drift < 1e-3);
}

TEST_CASE("elastic-plastic bar impact: precursor at the Hugoniot elastic limit, plastic wave at "
          "the bulk speed",
          "[sph][solid]") {
  // Perfect J2 plasticity in uniaxial strain (e.g. Meyers 1994, ch. 7): the elastic precursor
  // carries the Hugoniot elastic limit sigma_HEL = sigma_y (K + 4G/3) / (2G) at c_L and raises
  // the particle velocity by sigma_HEL / (rho c_L); the plastic wave runs at c_p = sqrt(K / rho)
  // and brings the rest of v0: sigma_final = sigma_HEL + rho c_p (v0 - sigma_HEL / (rho c_L)).
  const double v0 = 100.0, sy = 300e6, t = 6e-6, rho = 2700.0, K = 70e9, G = 26e9;
  const double cl = std::sqrt((K + 4.0 / 3.0 * G) / rho), cp = std::sqrt(K / rho);
  const double hel = sy * (K + 4.0 / 3.0 * G) / (2.0 * G);
  const double final_stress = hel + rho * cp * (v0 - hel / (rho * cl));
  const BarImpact r = bar_impact(v0, sy, t);
  std::printf("  plastic bar: precursor %.4g MPa (HEL %.4g), final %.4g MPa (theory %.4g), "
              "front speeds %.0f and %.0f m/s (c_L %.0f, c_p %.0f), energy drift %.2e\n",
              r.elastic_stress / 1e6, -hel / 1e6, r.final_stress / 1e6, -final_stress / 1e6,
              r.elastic_speed, r.plastic_speed, cl, cp, r.energy_drift);
  // Measured: precursor +1.4%, final stress +0.8%, speeds -0.8% (elastic), -0.7% (plastic).
  CHECK(r.elastic_stress == Approx(-hel).epsilon(0.02));
  CHECK(r.final_stress == Approx(-final_stress).epsilon(0.02));
  CHECK(r.plastic_speed == Approx(cp).epsilon(0.02));
  CHECK(r.elastic_speed == Approx(cl).epsilon(0.02));
  CHECK(r.energy_drift < 1e-3);
}

TEST_CASE("deviatoric radial return agrees with the implicit J2 update", "[sph][j2]") {
  // The same backward-Euler step from the same committed state: j2_update_3d on a total strain
  // and j2_radial_return on the elastic trial deviator of that strain.
  materials::J2Parameters p;
  p.E = 200e9;
  p.nu = 0.3;
  p.sigma0 = 450e6;
  p.hardening = materials::VoceHardening{129.24e6, 715e6, 16.93};
  const double mu = p.E / (2.0 * (1.0 + p.nu));
  for (double scale : {0.5, 1.2, 3.0, 10.0}) {
    materials::Vec6 strain;
    strain << 1.0e-3, -0.4e-3, -0.2e-3, 0.3e-3, 0.0, 0.5e-3; // engineering shears
    strain *= scale;
    materials::MaterialState committed;
    committed.alpha = 0.01;
    const materials::StressUpdate3D implicit = materials::j2_update_3d(p, strain, committed);
    // Trial deviator 2 mu e' (tensor shears = engineering / 2).
    const double tr = strain(0) + strain(1) + strain(2);
    materials::Vec6 s;
    for (int k = 0; k < 3; ++k) s(k) = 2.0 * mu * (strain(k) - tr / 3.0);
    for (int k = 3; k < 6; ++k) s(k) = mu * strain(k);
    const materials::J2Return r =
        materials::j2_radial_return(p, s, materials::Vec6::Zero(), committed.alpha);
    INFO("strain scale " << scale);
    CHECK(r.alpha == Approx(implicit.state.alpha).epsilon(1e-10));
    CHECK(materials::von_mises_3d(r.deviator) ==
          Approx(materials::von_mises_3d(implicit.stress)).epsilon(1e-10));
  }
}

TEST_CASE("SPH's deviatoric update with kinematic hardening follows j2_update_3d along a strain "
          "path",
          "[sph][j2]") {
  // A solid particle integrates its deviator, S_trial = S_n + 2 mu de' (no rotation), carries
  // its back stress and plastic strain, and returns with j2_radial_return; the Galerkin update
  // takes the total strain and the committed state. Along a path that yields, reverses
  // (Bauschinger) and yields again, both give the same deviator, back stress and plastic strain.
  materials::J2Parameters p;
  p.E = 200e9;
  p.nu = 0.3;
  p.sigma0 = 300e6;
  p.hardening = materials::LinearHardening{1.0e9};
  p.H_kinematic = 5.0e9;
  const double mu = p.E / (2.0 * (1.0 + p.nu));
  materials::Vec6 direction;
  direction << 1.0, -0.3, -0.5, 0.4, -0.2, 0.6; // engineering shears
  const std::vector<double> path = {0.5e-3,  1.0e-3,  2.0e-3,  3.0e-3, 1.5e-3, 0.0,
                                    -1.5e-3, -3.0e-3, -2.0e-3, 1.0e-3, 4.0e-3};
  materials::MaterialState galerkin;
  materials::Vec6 S = materials::Vec6::Zero(), beta = materials::Vec6::Zero();
  double alpha = 0.0, previous = 0.0;
  int plastic_steps = 0;
  for (double level : path) {
    const materials::Vec6 strain = level * direction;
    const materials::StressUpdate3D implicit = materials::j2_update_3d(p, strain, galerkin);
    galerkin = implicit.state;
    // The deviatoric strain increment (tensor shears = engineering / 2).
    const materials::Vec6 de = (level - previous) * direction;
    const double tr = de(0) + de(1) + de(2);
    materials::Vec6 trial = S;
    for (int k = 0; k < 3; ++k) trial(k) += 2.0 * mu * (de(k) - tr / 3.0);
    for (int k = 3; k < 6; ++k) trial(k) += mu * de(k);
    const materials::J2Return r = materials::j2_radial_return(p, trial, beta, alpha);
    S = r.deviator, beta = r.back_stress, alpha = r.alpha, previous = level;
    plastic_steps += r.plastic ? 1 : 0;
    INFO("strain level " << level);
    CHECK(r.plastic == implicit.plastic);
    const double mean = implicit.stress.head<3>().sum() / 3.0;
    for (int k = 0; k < 6; ++k) {
      CHECK(S(k) == Approx(implicit.stress(k) - (k < 3 ? mean : 0.0)).margin(1e-12 * p.sigma0));
      CHECK(beta(k) == Approx(galerkin.back_stress(k)).margin(1e-12 * p.sigma0));
    }
    CHECK(alpha == Approx(galerkin.alpha).epsilon(1e-12));
  }
  CHECK(plastic_steps >= 6);
  CHECK(galerkin.back_stress.norm() > 0.0);
}

TEST_CASE("an SPH particle with kinematic hardening carries its back stress between steps like "
          "j2_update_3d",
          "[sph][j2]") {
  // One solid particle driven through update_stress by prescribed rates (no spin): each step's
  // deviatoric rate is 2G de' / dt, and the particle's stress, back stress and plastic strain
  // follow the Galerkin update of the total strain (E = 2G, nu = 0, so the return's mu is G).
  const double G = 26e9;
  materials::VonMises vm;
  vm.shear_modulus = G;
  vm.j2.E = 2.0 * G;
  vm.j2.nu = 0.0;
  vm.j2.sigma0 = 150e6;
  vm.j2.hardening = materials::LinearHardening{0.5e9};
  vm.j2.H_kinematic = 2.0e9;
  sph::Hydro s;
  s.dim = 3;
  sph::Material solid = test_solid();
  solid.strength = vm;
  s.materials.push_back(solid);
  const double x[3] = {0.0, 0.0, 0.0};
  add(s, x, 1.0 / 2700.0, 2700.0, 0.0, 1.0, 0);
  sph::group_materials(s);
  materials::Vec6 direction; // engineering shears
  direction << 1.0, -0.2, -0.6, 0.3, 0.5, -0.4;
  const std::vector<double> path = {1.0e-3, 2.5e-3, 4.0e-3, 2.0e-3, -1.0e-3, -4.0e-3, 0.0, 5.0e-3};
  materials::MaterialState galerkin;
  double previous = 0.0;
  int plastic_steps = 0;
  for (double level : path) {
    const materials::StressUpdate3D implicit =
        materials::j2_update_3d(vm.j2, level * direction, galerkin);
    galerkin = implicit.state;
    plastic_steps += implicit.plastic ? 1 : 0;
    const materials::Vec6 de = (level - previous) * direction;
    const double tr = de(0) + de(1) + de(2);
    sph::Rates r;
    r.dS.assign(6, 0.0);
    r.grad_v.assign(9, 0.0);
    for (int k = 0; k < 3; ++k) r.dS[k] = 2.0 * G * (de(k) - tr / 3.0);
    for (int k = 3; k < 6; ++k) r.dS[k] = G * de(k);
    // A symmetric velocity gradient over dt = 1 (the strain rate only).
    const double D[9] = {de(0),     de(5) / 2, de(4) / 2, de(5) / 2, de(1),
                         de(3) / 2, de(4) / 2, de(3) / 2, de(2)};
    for (int k = 0; k < 9; ++k) r.grad_v[k] = D[k];
    sph::update_stress(s, sph::stress_history(s), r, 1.0);
    previous = level;
    INFO("strain level " << level);
    const double mean = implicit.stress.head<3>().sum() / 3.0;
    for (int k = 0; k < 6; ++k) {
      CHECK(s.fields.S[k] ==
            Approx(implicit.stress(k) - (k < 3 ? mean : 0.0)).margin(1e-12 * vm.j2.sigma0));
      CHECK(s.fields.back_stress[k] ==
            Approx(galerkin.back_stress(k)).margin(1e-12 * vm.j2.sigma0));
    }
    CHECK(s.fields.alpha[0] == Approx(galerkin.alpha).epsilon(1e-12));
  }
  CHECK(plastic_steps >= 4);
}

TEST_CASE("plane elastic wave in a 2D and a 3D block: stress behind the front",
          "[sph][solid][long]") {
  // Two blocks meet at x = 0 with velocities +-v0; near the centre line the state is uniaxial
  // strain until the lateral release waves from the free sides arrive (after half the width over
  // c_L). Behind the front sigma_xx = -rho c_L v0 (the 1D test's material, h = 1.5 dx: the SPH
  // gradient of a linear field on these lattices is within 1% of exact).
  const double v0 = 1.0, K = 70e9, G = 26e9, rho = 2700.0;
  const double cl = std::sqrt((K + 4.0 / 3.0 * G) / rho);
  for (int dim : {2, 3}) {
    sph::Hydro s;
    s.dim = dim;
    s.materials.push_back(test_solid());
    const double dx = 0.5e-3, half = 8e-3; // half-width across; the blocks are 10 mm long
    const int nx = static_cast<int>(std::lround(2 * 0.01 / dx)),
              ny = static_cast<int>(std::lround(2 * half / dx)), nz = dim == 3 ? ny : 1;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const double x[3] = {-0.01 + (i + 0.5) * dx, -half + (j + 0.5) * dx,
                               dim == 3 ? -half + (k + 0.5) * dx : 0.0};
          add(s, x, std::pow(dx, dim), rho, 0.0, 1.5 * dx, 0);
          s.particles.v[s.particles.v.size() - 3] = x[0] < 0.0 ? v0 : -v0;
        }
    sph::update_state(s);
    const double t_end = 0.8 * half / cl; // before the lateral release reaches the centre
    const double e0 = sph::energies(s).total();
    while (s.particles.time < t_end)
      sph::advance(s, std::min(sph::stable_step(s), t_end - s.particles.time));
    const particles::ParticleSet& P = s.particles;
    const sph::ParticleFields& F = s.fields;
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < P.size(); ++i) {
      const double x = (P.X[3 * i] + P.u[3 * i]), r = std::hypot((P.X[3 * i + 1] + P.u[3 * i + 1]),
                                                                 (P.X[3 * i + 2] + P.u[3 * i + 2]));
      if (x > 0.1 * cl * t_end && x < 0.7 * cl * t_end && r < 0.1 * half)
        sum += -F.p[i] + F.S[6 * i], ++count;
    }
    const double sxx = sum / count;
    const double drift = std::abs(sph::energies(s).total() - e0) / e0;
    std::printf("  %dD block (%d particles): sigma_xx %.4g MPa (theory %.4g) over %d particles, "
                "energy drift %.2e\n",
                dim, P.size(), sxx / 1e6, -rho * cl * v0 / 1e6, count, drift);
    INFO(dim << "D");
    // Measured: -0.5% (2D), -0.6% (3D); energy error 1.0e-3 (2D) and 2.0e-4 (3D), held to the
    // issue's 1% for runs without dissipation leaving the system.
    CHECK(sxx == Approx(-rho * cl * v0).epsilon(0.02));
    CHECK(drift < 0.01);
  }
}

TEST_CASE("a blast gives a free SPH plate the momentum of the Kingery-Bulmash impulses",
          "[sph][blast]") {
  // problems/sph_plate_blast.yaml at 10 mm spacing: after every positive phase has ended the
  // plate's y-momentum must be -sum_k A_k I_k (A_k = dx per metre of width, I_k the impulse of the
  // top-row particle's Friedlander history, computed here from the geometry), and kinetic plus
  // internal energy must equal the work of the loads.
  const double dx = 0.01;
  const spec::ProblemSpec spec = load_problem(
      "sph_plate_blast",
      {"regions.0.spacing=0.01", "boundary.0.box=[[0, 0.04], [1.0, 0.05]]", "time.end=1.6e-3"});
  double expected = 0.0, peak_force = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double x = (k + 0.5) * dx, y = 0.045;
    const double rx = x - 0.5, ry = y - 0.55, r = std::hypot(rx, ry);
    const loads::BlastParameters b = kingery_bulmash(loads::Burst::SphericalFreeAir, 1.0, r);
    const loads::Friedlander f = blast_pulse(b, -ry / r);
    expected += dx * f.impulse();
    peak_force += dx * f.peak;
  }
  sph::Hydro h = explicit_dynamics::build_sph(spec.sph());
  REQUIRE(h.conditions.size() == 1);
  REQUIRE(h.conditions.of_kind<sph::SurfaceLoad>().size() == 1);
  REQUIRE(h.conditions.of_kind<sph::SurfaceLoad>()[0]->particles.size() == 100);
  const double e0 = sph::energies(h).total();
  double dt_max = 0.0;
  while (h.particles.time < spec.sph().end_time) {
    const double dt = std::min(sph::stable_step(h), spec.sph().end_time - h.particles.time);
    dt_max = std::max(dt_max, dt);
    sph::advance(h, dt);
  }
  const particles::ParticleSet& P = h.particles;
  double py = 0.0;
  for (int i = 0; i < P.size(); ++i) py += P.mass[i] * P.v[3 * i + 1];
  const double balance =
      std::abs(sph::energies(h).total() - e0 - h.external_work) / h.external_work;
  std::printf("  SPH plate blast: momentum %.6g against %.6g (%.2e), energy balance %.2e, "
              "%ld steps\n",
              py, -expected, std::abs(py + expected) / expected, balance, h.particles.step);
  // The midpoint step integrates the smooth decay to O(dt^2); the jump at arrival costs at most
  // P_k dt / 2 per particle (measured 1.0e-3 relative in all, within that bound).
  CHECK(std::abs(py + expected) <= 0.5 * dt_max * peak_force);
  CHECK(std::abs(py + expected) < 0.005 * expected);
  CHECK(balance < 0.01);
}

TEST_CASE("a transmitting boundary absorbs an elastic pulse", "[sph][solid]") {
  // A smooth velocity pulse (v0 sin^2 over 20 mm) in a 100 mm elastic bar (uniaxial strain, h =
  // 2 dx) splits into two waves; the left one reflects from the free end, both leave through a
  // Lysmer dashpot (traction -rho c_L v) on the last particle. Afterwards the largest velocity in
  // the bar measures the reflection from the dashpot (a free end would reflect all of it), and
  // the energy it absorbed is the work of the boundary.
  const double K = 70e9, G = 26e9, rho = 2700.0, v0 = 1.0;
  const double cl = std::sqrt((K + 4.0 / 3.0 * G) / rho);
  double reflected[2];
  for (int absorbing : {0, 1}) {
    sph::Hydro s;
    s.dim = 1;
    s.materials.push_back(test_solid());
    const int n = 400;
    const double dx = 0.1 / n;
    for (int k = 0; k < n; ++k) {
      const double x[3] = {(k + 0.5) * dx, 0, 0};
      add(s, x, dx, rho, 0.0, 2.0 * dx, 0);
      if (x[0] > 0.02 && x[0] < 0.04)
        s.particles.v[3 * k] = v0 * std::pow(std::sin(M_PI * (x[0] - 0.02) / 0.02), 2);
    }
    if (absorbing) {
      sph::TransmittingBoundary b;
      b.name = "right";
      b.particles = {n - 1};
      b.area = {1.0};
      b.normal_impedance = {rho * cl};
      b.shear_impedance = {rho * std::sqrt(G / rho)};
      b.normal[0] = 1.0;
      s.conditions.add(b);
    }
    sph::update_state(s);
    const double e0 = sph::energies(s).total();
    const double t_end = (0.03 + 0.1 + 0.03) / cl; // the reflected wave has left
    while (s.particles.time < t_end)
      sph::advance(s, std::min(sph::stable_step(s), t_end - s.particles.time));
    double vmax = 0.0;
    for (int i = 0; i < n; ++i) vmax = std::max(vmax, std::abs(s.particles.v[3 * i]));
    reflected[absorbing] = vmax / (0.5 * v0);
    const sph::Energies E = sph::energies(s);
    std::printf("  %s right end: largest |v| %.4f of the incident half-pulse, kinetic energy "
                "%.3e of the start, boundary work %.3e, balance %.2e\n",
                absorbing ? "transmitting" : "free", reflected[absorbing], E.kinetic / e0,
                s.external_work / e0, std::abs(E.total() - e0 - s.external_work) / e0);
    // Measured: free end 0.72 of the half-pulse left, kinetic energy 0.34 of the start; dashpot
    // 0.057 (the dispersive tail SPH leaves behind any pulse) and 1.5e-3, with 74% of the
    // energy absorbed (the rest is the viscosity's heat).
    if (absorbing) {
      CHECK(reflected[1] < 0.1);
      CHECK(E.kinetic < 0.01 * e0);
      CHECK(std::abs(E.total() - e0 - s.external_work) < 0.01 * e0);
    }
  }
  CHECK(reflected[0] > 0.5); // the free end sends the pulse back
}

namespace {
/// Two elastic 2D blocks (30 x 10 mm each, dx = 0.5 mm, h = 1.3 dx) pulled apart at 60 m/s each,
/// without artificial viscosity: the tension behind the two release fronts (about 0.6-0.9 GPa)
/// is where SPH particles pair up (Swegle et al. 1995). Returns the closest pair among the
/// particles that started within 10 mm of the middle after 8 us, in initial spacings.
double pulled_blocks_closest_pair(double epsilon) {
  sph::Hydro s;
  s.dim = 2;
  s.materials.push_back(test_solid());
  s.settings.alpha = s.settings.beta = 0.0;
  s.settings.artificial_stress = epsilon;
  const double dx = 0.5e-3;
  std::vector<int> middle;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 120; ++i) {
      const double x[3] = {-0.03 + (i + 0.5) * dx, (j + 0.5) * dx, 0};
      add(s, x, dx * dx, 2700.0, 0.0, 1.3 * dx, 0);
      s.particles.v[s.particles.v.size() - 3] = x[0] < 0.0 ? -60.0 : 60.0;
      if (std::abs(x[0]) < 0.01) middle.push_back(s.particles.size() - 1);
    }
  sph::update_state(s);
  while (s.particles.time < 8e-6)
    sph::advance(s, std::min(sph::stable_step(s), 8e-6 - s.particles.time));
  const particles::ParticleSet& P = s.particles;
  double closest = 1e300;
  for (std::size_t a = 0; a < middle.size(); ++a)
    for (std::size_t b = a + 1; b < middle.size(); ++b) {
      const int i = middle[a], j = middle[b];
      closest = std::min(closest, std::hypot((P.X[3 * i] + P.u[3 * i]) - (P.X[3 * j] + P.u[3 * j]),
                                             (P.X[3 * i + 1] + P.u[3 * i + 1]) -
                                                 (P.X[3 * j + 1] + P.u[3 * j + 1])));
    }
  return closest / dx;
}
} // namespace

TEST_CASE("artificial stress prevents the tensile instability", "[sph][solid]") {
  // Without it the particles in tension pair up to 0.54 dx within 8 us; with epsilon = 0.3 the
  // lattice stays within 2% of its spacing (measured 0.536 and 0.984 dx).
  const double plain = pulled_blocks_closest_pair(0.0);
  const double stressed = pulled_blocks_closest_pair(0.3);
  std::printf("  blocks pulled apart: closest pair %.3f dx without, %.3f dx with artificial "
              "stress\n",
              plain, stressed);
  CHECK(plain < 0.7);
  CHECK(stressed > 0.95);
}

TEST_CASE("artificial stress: pairwise terms keep momentum and energy in a block under tension",
          "[sph][solid]") {
  // A free 2D elastic block (20 x 20 mm, dx = 0.5 mm, h = 1.3 dx, lattice jittered by +-2% dx)
  // set expanding with v = rate (x - centre): it decelerates under a growing hydrostatic
  // tension, where the artificial stress acts. Its pair terms are antisymmetric, so the
  // momentum stays zero, and they enter the energy equation like the stress, so the energy is
  // kept.
  sph::Hydro s;
  s.dim = 2;
  s.materials.push_back(test_solid());
  s.settings.artificial_stress = 0.3;
  const int n = 40;
  const double dx = 0.02 / n, rate = 1500.0;
  unsigned seed = 12345u;
  const auto jitter = [&]() {
    seed = seed * 1664525u + 1013904223u;
    return 0.04 * dx * (static_cast<double>(seed >> 8) / 16777216.0 - 0.5);
  };
  double p0[2] = {0.0, 0.0};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x[3] = {(i + 0.5) * dx - 0.01 + jitter(), (j + 0.5) * dx - 0.01 + jitter(), 0};
      add(s, x, dx * dx, 2700.0, 0.0, 1.3 * dx, 0);
      s.particles.v[s.particles.v.size() - 3] = rate * x[0];
      s.particles.v[s.particles.v.size() - 2] = rate * x[1];
      p0[0] += 2700.0 * dx * dx * rate * x[0];
      p0[1] += 2700.0 * dx * dx * rate * x[1];
    }
  sph::update_state(s);
  const double e0 = sph::energies(s).total();
  double tension = 0.0;
  while (s.particles.time < 4e-6) {
    sph::advance(s, std::min(sph::stable_step(s), 4e-6 - s.particles.time));
    tension = std::max(tension, -*std::min_element(s.fields.p.begin(), s.fields.p.end()));
  }
  const particles::ParticleSet& P = s.particles;
  double mom[2] = {0.0, 0.0}, scale = 0.0;
  for (int i = 0; i < P.size(); ++i)
    for (int d = 0; d < 2; ++d) {
      mom[d] += P.mass[i] * P.v[3 * i + d];
      scale += P.mass[i] * rate * 0.01;
    }
  const double drift = std::abs(sph::energies(s).total() - e0) / e0;
  std::printf("  tension block: largest tension %.3g MPa, momentum %.1e, energy drift %.1e\n",
              tension / 1e6, std::hypot(mom[0] - p0[0], mom[1] - p0[1]) / scale, drift);
  CHECK(tension > 50e6);
  CHECK(std::abs(mom[0] - p0[0]) < 1e-12 * scale);
  CHECK(std::abs(mom[1] - p0[1]) < 1e-12 * scale);
  CHECK(drift < 1e-3);
}

namespace {
/// A 2D elastic-plastic block [-L, L] x [-H, H] (L = 10, H = 6 mm, dx = 0.25 mm) squeezed by
/// the initial velocity v = -rate (x, 2y): the whole block, or its quarter x, y > 0 with
/// symmetry planes x = 0 and y = 0. Returns the particles' states after 4 us in the order
/// (x, y, vx, vy, p, Sxy) for the quarter's particles (matched by their initial position).
std::vector<std::array<double, 6>> squeezed_block(bool quarter) {
  sph::Hydro s;
  s.dim = 2;
  s.materials.push_back(test_solid(300e6));
  const double dx = 0.25e-3, L = 10e-3, H = 6e-3, rate = 1.5e4;
  const int nx = static_cast<int>(std::lround(2 * L / dx)),
            ny = static_cast<int>(std::lround(2 * H / dx));
  std::vector<int> keep;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x[3] = {-L + (i + 0.5) * dx, -H + (j + 0.5) * dx, 0};
      if (quarter && (x[0] < 0 || x[1] < 0)) continue;
      add(s, x, dx * dx, 2700.0, 0.0, 1.5 * dx, 0);
      const std::size_t k = s.particles.v.size() - 3;
      s.particles.v[k] = -rate * x[0];
      s.particles.v[k + 1] = -2.0 * rate * x[1];
      if (x[0] > 0 && x[1] > 0) keep.push_back(s.particles.size() - 1);
    }
  if (quarter) s.symmetry = {{0, 0.0}, {1, 0.0}};
  sph::update_state(s);
  while (s.particles.time < 4e-6)
    sph::advance(s, std::min(sph::stable_step(s), 4e-6 - s.particles.time));
  const particles::ParticleSet& P = s.particles;
  const sph::ParticleFields& F = s.fields;
  std::vector<std::array<double, 6>> out;
  for (int i : keep)
    out.push_back({(P.X[3 * i] + P.u[3 * i]), (P.X[3 * i + 1] + P.u[3 * i + 1]), P.v[3 * i],
                   P.v[3 * i + 1], F.p[i], F.S[6 * i + 5]});
  return out;
}
} // namespace

TEST_CASE("symmetry planes: a quarter model reproduces the whole body", "[sph][solid]") {
  // The mirror particles stand for the missing three quarters exactly, corners included, so the
  // quarter's particles must follow their counterparts in the whole block to round-off.
  const auto whole = squeezed_block(false), quarter = squeezed_block(true);
  REQUIRE(whole.size() == quarter.size());
  double scale[6] = {10e-3, 6e-3, 150.0, 180.0, 0.0, 0.0}, worst[6] = {0, 0, 0, 0, 0, 0};
  for (const auto& w : whole) {
    scale[4] = std::max(scale[4], std::abs(w[4]));
    scale[5] = std::max(scale[5], std::abs(w[5]));
  }
  for (std::size_t k = 0; k < whole.size(); ++k)
    for (int c = 0; c < 6; ++c)
      worst[c] = std::max(worst[c], std::abs(whole[k][c] - quarter[k][c]) / scale[c]);
  std::printf("  quarter vs whole (%zu particles): position %.1e, velocity %.1e / %.1e, pressure "
              "%.1e (peak %.3g MPa), shear stress %.1e (peak %.3g MPa)\n",
              whole.size(), std::max(worst[0], worst[1]), worst[2], worst[3], worst[4],
              scale[4] / 1e6, worst[5], scale[5] / 1e6);
  CHECK(scale[5] > 10e6); // the squeeze does raise shear stresses, which the mirror flips
  for (int c = 0; c < 6; ++c) CHECK(worst[c] < 1e-9);
}
