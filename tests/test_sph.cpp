// SPH hydrodynamics: the kernel, the equations of state against the jump conditions they must
// satisfy, Sod's shock tube against the exact Riemann solution, and a TNT slab detonation
// against the Chapman-Jouguet pressure.
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
#include "sph_test_support.hpp"
#include "test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

using namespace mf;

TEST_CASE("cubic spline and Wendland C2 kernels have unit integral and consistent slopes",
          "[sph]") {
  using Kernel = double (*)(int, double, double);
  const struct {
    const char* name;
    Kernel W, slope;
  } kinds[] = {{"cubic spline", kernels::cubic_spline, kernels::cubic_spline_slope},
               {"Wendland C2", kernels::wendland_c2, kernels::wendland_c2_slope}};
  const double h = 0.7;
  for (const auto& kind : kinds)
    for (int dim = 1; dim <= 3; ++dim) {
      INFO(kind.name << ", dim " << dim);
      // Integral of W over its support by the radial rule in dim dimensions.
      const int n = 20000;
      double integral = 0.0;
      for (int k = 0; k < n; ++k) {
        const double r = (k + 0.5) * 2.0 * h / n, dr = 2.0 * h / n;
        const double shell = dim == 1 ? 2.0 : dim == 2 ? 2.0 * M_PI * r : 4.0 * M_PI * r * r;
        integral += kind.W(dim, r, h) * shell * dr;
      }
      CHECK(integral == Approx(1.0).epsilon(1e-6));
      for (double r : {0.1, 0.5, 0.69, 0.71, 1.0, 1.3}) {
        const double d = 1e-6;
        const double fd = (kind.W(dim, r + d, h) - kind.W(dim, r - d, h)) / (2 * d);
        CHECK(kind.slope(dim, r, h) == Approx(fd).epsilon(1e-6));
      }
      CHECK(kind.W(dim, 2.0 * h, h) == 0.0);
    }
}

namespace {
/// c^2 = dp/drho|_e + p/rho^2 dp/de|_rho by central differences.
template <class F> double sound_speed_fd(F p, double rho, double e) {
  const double dr = 1e-6 * rho, de = 1e-6 * std::max(std::abs(e), 1.0);
  const double dpdr = (p(rho + dr, e) - p(rho - dr, e)) / (2 * dr);
  const double dpde = (p(rho, e + de) - p(rho, e - de)) / (2 * de);
  return dpdr + p(rho, e) / (rho * rho) * dpde;
}
} // namespace

TEST_CASE("equations of state: sound speeds and the shock jump conditions", "[sph][eos]") {
  const materials::IdealGas air{1.4};
  CHECK(materials::ideal_gas(air, 1.225, 2.068e5).p == Approx(0.4 * 1.225 * 2.068e5));
  const materials::Jwl tnt;
  for (double rho : {1000.0, 1630.0, 2200.0}) {
    const double e = 3e6;
    const auto p = [&](double r, double en) { return materials::jwl(tnt, r, en).p; };
    CHECK(materials::jwl(tnt, rho, e).c2 == Approx(sound_speed_fd(p, rho, e)).epsilon(1e-5));
  }
  // Copper (Steinberg 1996: rho0 8930, c0 3940, s 1.49, Gamma0 2.0) shocked to u_p = 500 m/s:
  // the Rankine-Hugoniot jumps give U_s = c0 + s u_p, p = rho0 U_s u_p,
  // rho = rho0 U_s / (U_s - u_p) and e = u_p^2 / 2; Mie-Grueneisen must return that p there.
  const materials::MieGruneisen cu{8930.0, 3940.0, 1.49, 2.0};
  for (double up : {100.0, 500.0, 1000.0}) {
    const double us = cu.c0 + cu.s * up;
    const double rho = cu.rho0 * us / (us - up), e = 0.5 * up * up;
    CHECK(materials::mie_gruneisen(cu, rho, e).p == Approx(cu.rho0 * us * up).epsilon(1e-10));
    const auto p = [&](double r, double en) { return materials::mie_gruneisen(cu, r, en).p; };
    CHECK(materials::mie_gruneisen(cu, rho, e).c2 ==
          Approx(sound_speed_fd(p, rho, e)).epsilon(1e-5));
  }
  const auto p_ten = [&](double r, double en) { return materials::mie_gruneisen(cu, r, en).p; };
  CHECK(materials::mie_gruneisen(cu, 8800.0, 1e4).c2 ==
        Approx(sound_speed_fd(p_ten, 8800.0, 1e4)).epsilon(1e-5));
  // A linear polynomial with C1 = K is a linear elastic solid: c^2 = K / rho0 at rho0.
  materials::LinearPolynomial lin;
  lin.rho0 = 2700.0;
  lin.c[1] = 70e9;
  CHECK(materials::linear_polynomial(lin, 2700.0, 0.0).c2 == Approx(70e9 / 2700.0));
}

TEST_CASE("JWL TNT: the Chapman-Jouguet point of the Dobratz constants", "[sph][eos]") {
  // The Rayleigh line p = rho0 D^2 (1 - V) (V = rho0/rho) touches the products' Hugoniot
  // e = e0 + p (1 - V) / (2 rho0) at the CJ point, where the flow behind the front is sonic:
  // c_CJ = D V_CJ (Fickett & Davis 1979, ch. 2). The Hugoniot lies above the line except there:
  // scan V for the smallest gap.
  const materials::Jwl tnt;
  const double D = tnt.detonation_speed, r0 = tnt.rho0;
  double best_gap = 1e300, v_cj = 0.0;
  for (double V = 0.6; V < 0.9; V += 1e-6) {
    const double pr = r0 * D * D * (1.0 - V);
    const double e = tnt.e0 + pr * (1.0 - V) / (2.0 * r0);
    const double gap = materials::jwl(tnt, r0 / V, e).p - pr;
    if (gap < best_gap) best_gap = gap, v_cj = V;
  }
  const double p_cj = r0 * D * D * (1.0 - v_cj);
  const double e_cj = tnt.e0 + p_cj * (1.0 - v_cj) / (2.0 * r0);
  const double c_cj = std::sqrt(materials::jwl(tnt, r0 / v_cj, e_cj).c2);
  std::printf("  JWL TNT CJ point: V %.4f, p %.2f GPa (handbook 21), gap %.3g GPa, "
              "c_CJ / (D V_CJ) %.4f\n",
              v_cj, p_cj / 1e9, best_gap / 1e9, c_cj / (D * v_cj));
  CHECK(std::abs(best_gap) < 0.02 * p_cj); // tangent: the line just touches
  CHECK(p_cj == Approx(tnt.cj_pressure).epsilon(0.03));
  CHECK(c_cj == Approx(D * v_cj).epsilon(0.02));
}

namespace {

/// Toro's exact solution of the Riemann problem of an ideal gas (Toro 2009, ch. 4): the sampled
/// density, velocity and pressure at x / t.
struct Riemann {
  double rl, ul, pl, rr, ur, pr, g;
  double p_star = 0.0, u_star = 0.0;

  double f(double p, double rk, double pk, double& df) const {
    const double ck = std::sqrt(g * pk / rk);
    if (p > pk) { // shock
      const double A = 2.0 / ((g + 1.0) * rk), B = (g - 1.0) / (g + 1.0) * pk;
      const double s = std::sqrt(A / (p + B));
      df = s * (1.0 - 0.5 * (p - pk) / (B + p));
      return (p - pk) * s;
    }
    const double pr_ = p / pk; // rarefaction
    df = 1.0 / (rk * ck) * std::pow(pr_, -(g + 1.0) / (2.0 * g));
    return 2.0 * ck / (g - 1.0) * (std::pow(pr_, (g - 1.0) / (2.0 * g)) - 1.0);
  }

  void solve() {
    double p = 0.5 * (pl + pr);
    for (int k = 0; k < 100; ++k) {
      double dl, dr;
      const double F = f(p, rl, pl, dl) + f(p, rr, pr, dr) + (ur - ul);
      const double next = std::max(1e-12, p - F / (dl + dr));
      if (std::abs(next - p) < 1e-14 * p) break;
      p = next;
    }
    double dl, dr;
    p_star = p;
    u_star = 0.5 * (ul + ur) + 0.5 * (f(p, rr, pr, dr) - f(p, rl, pl, dl));
  }

  /// rho, u, p at s = x / t.
  void sample(double s, double& rho, double& u, double& p) const {
    const double gm = (g - 1.0) / (g + 1.0);
    if (s <= u_star) { // left of the contact
      const double cl = std::sqrt(g * pl / rl);
      if (p_star > pl) {
        const double sl =
            ul - cl * std::sqrt((g + 1.0) / (2 * g) * p_star / pl + (g - 1) / (2 * g));
        if (s < sl) {
          rho = rl, u = ul, p = pl;
          return;
        }
        rho = rl * (p_star / pl + gm) / (gm * p_star / pl + 1.0), u = u_star, p = p_star;
        return;
      }
      const double c_star = cl * std::pow(p_star / pl, (g - 1) / (2 * g));
      if (s < ul - cl) {
        rho = rl, u = ul, p = pl;
        return;
      }
      if (s > u_star - c_star) {
        rho = rl * std::pow(p_star / pl, 1.0 / g), u = u_star, p = p_star;
        return;
      }
      u = 2.0 / (g + 1) * (cl + (g - 1) / 2 * ul + s);
      const double c = 2.0 / (g + 1) * (cl + (g - 1) / 2 * (ul - s));
      rho = rl * std::pow(c / cl, 2.0 / (g - 1)), p = pl * std::pow(c / cl, 2 * g / (g - 1));
      return;
    }
    const double cr = std::sqrt(g * pr / rr);
    if (p_star > pr) {
      const double sr = ur + cr * std::sqrt((g + 1.0) / (2 * g) * p_star / pr + (g - 1) / (2 * g));
      if (s > sr) {
        rho = rr, u = ur, p = pr;
        return;
      }
      rho = rr * (p_star / pr + gm) / (gm * p_star / pr + 1.0), u = u_star, p = p_star;
      return;
    }
    const double c_star = cr * std::pow(p_star / pr, (g - 1) / (2 * g));
    if (s > ur + cr) {
      rho = rr, u = ur, p = pr;
      return;
    }
    if (s < u_star + c_star) {
      rho = rr * std::pow(p_star / pr, 1.0 / g), u = u_star, p = p_star;
      return;
    }
    u = 2.0 / (g + 1) * (-cr + (g - 1) / 2 * ur + s);
    const double c = 2.0 / (g + 1) * (cr - (g - 1) / 2 * (ur - s));
    rho = rr * std::pow(c / cr, 2.0 / (g - 1)), p = pr * std::pow(c / cr, 2 * g / (g - 1));
  }
};

struct SodResult {
  double l1_density = 0.0;                 // mean |rho - exact| over -0.4 < x < 0.4
  double plateau_p = 0.0, plateau_u = 0.0; // mean over the star region away from its edges
  double shock_x = 0.0;                    // where rho crosses (rho*_R + rho_R) / 2
  double energy_drift = 0.0;               // |E(t) - E(0)| / E(0)
  int particles = 0;
};

/// Sod's tube on [-1, 1] between fixed walls with equal-mass particles: n_left on the left (rho 1,
/// p 1), n_left / 8 on the right (rho 0.125, p 0.1), h = 1.5 local spacings; run to t = 0.2.
SodResult run_sod(int n_left, const Riemann& exact,
                  kernels::SphKernel kernel = kernels::SphKernel::CubicSpline) {
  sph::Hydro s;
  s.dim = 1;
  s.settings.kernel = kernel;
  sph::Material gas;
  gas.name = "gas";
  gas.eos = materials::IdealGas{1.4};
  s.materials.push_back(gas);
  const double dxl = 1.0 / n_left, dxr = 8.0 * dxl, m = dxl * 1.0;
  for (int k = 0; k < n_left; ++k) {
    const double x[3] = {-1.0 + (k + 0.5) * dxl, 0, 0};
    add(s, x, m, 1.0, 1.0 / (0.4 * 1.0), 1.5 * dxl, 0);
  }
  for (int k = 0; k < n_left / 8; ++k) {
    const double x[3] = {(k + 0.5) * dxr, 0, 0};
    add(s, x, 8.0 * m, 0.125, 0.1 / (0.4 * 0.125), 1.5 * dxr, 0);
  }
  // Closed ends: four fixed wall particles beyond each end (no wave reaches them by t = 0.2).
  for (int k = 1; k <= 4; ++k) {
    const double xl[3] = {-1.0 - (k - 0.5) * dxl, 0, 0}, xr[3] = {1.0 + (k - 0.5) * dxr, 0, 0};
    add(s, xl, m, 1.0, 1.0 / (0.4 * 1.0), 1.5 * dxl, 0, true);
    add(s, xr, 8.0 * m, 0.125, 0.1 / (0.4 * 0.125), 1.5 * dxr, 0, true);
  }
  sph::update_state(s);
  const double e0 = sph::energies(s).total();
  while (s.particles.time < 0.2) {
    const double dt = std::min(sph::stable_step(s), 0.2 - s.particles.time);
    sph::advance(s, dt);
  }
  SodResult out;
  out.particles = s.particles.size() - 8;
  out.energy_drift = std::abs(sph::energies(s).total() - e0) / e0;
  const particles::ParticleSet& P = s.particles;
  const sph::ParticleFields& F = s.fields;
  int count = 0, plateau = 0;
  const double rho_mid = 0.5 * (0.26557 + 0.125);
  const int n_gas = P.size() - 8;
  for (int i = 0; i + 1 < n_gas; ++i) {
    const double x = (P.X[3 * i] + P.u[3 * i]);
    double rho, u, p;
    exact.sample(x / 0.2, rho, u, p);
    if (x > -0.4 && x < 0.4) out.l1_density += std::abs(F.rho[i] - rho), ++count;
    // The star region between the contact (x = 0.185) and the shock (x = 0.350), away from the
    // pressure blip SPH leaves at the contact and from the smeared shock.
    if (x > 0.21 && x < 0.30) out.plateau_p += F.p[i], out.plateau_u += P.v[3 * i], ++plateau;
    const double x2 = (P.X[3 * (i + 1)] + P.u[3 * (i + 1)]);
    if (x > 0.2 && (F.rho[i] - rho_mid) * (F.rho[i + 1] - rho_mid) <= 0.0)
      out.shock_x = x + (x2 - x) * (F.rho[i] - rho_mid) / (F.rho[i] - F.rho[i + 1]);
  }
  out.l1_density /= count;
  out.plateau_p /= plateau;
  out.plateau_u /= plateau;
  return out;
}

} // namespace

TEST_CASE("Sod's shock tube against the exact Riemann solution", "[sph]") {
  Riemann exact{1.0, 0.0, 1.0, 0.125, 0.0, 0.1, 1.4};
  exact.solve();
  // Toro 2009, Table 4.2 (test 1): p* = 0.30313, u* = 0.92745.
  REQUIRE(exact.p_star == Approx(0.30313).epsilon(1e-4));
  REQUIRE(exact.u_star == Approx(0.92745).epsilon(1e-4));
  const double shock_speed = 1.75216; // Toro's test 1
  std::vector<double> l1, spacing, err_p, err_u, err_shock;
  for (int n : {400, 800, 1600}) {
    const SodResult r = run_sod(n, exact);
    std::printf("  Sod, %d particles (dx_left %.5f): L1(rho) %.4e, p* %.5f, u* %.5f, shock at "
                "%.4f (exact %.4f), energy drift %.2e\n",
                r.particles, 1.0 / n, r.l1_density, r.plateau_p, r.plateau_u, r.shock_x,
                0.2 * shock_speed, r.energy_drift);
    INFO(n << " particles on the left");
    CHECK(r.energy_drift < 1e-4); // no dissipation leaves the system: viscosity heats the gas
    l1.push_back(r.l1_density);
    spacing.push_back(1.0 / n);
    err_p.push_back(std::abs(r.plateau_p / exact.p_star - 1.0));
    err_u.push_back(std::abs(r.plateau_u / exact.u_star - 1.0));
    err_shock.push_back(std::abs(r.shock_x - 0.2 * shock_speed));
  }
  // Measured: p* -2.7%, -1.2%, -0.8%; u* -2.4%, -1.3%, -0.9%; shock 0.015, 0.010, 0.0067 behind.
  for (int k = 1; k < 3; ++k) {
    CHECK(err_p[k] < err_p[k - 1]);
    CHECK(err_u[k] < err_u[k - 1]);
    CHECK(err_shock[k] < err_shock[k - 1]);
    CHECK(l1[k] < l1[k - 1]);
  }
  CHECK(err_p[2] < 0.01);
  CHECK(err_u[2] < 0.01);
  CHECK(err_shock[2] < 0.01);
  // The contact discontinuity limits schemes with numerical dissipation to L1 order 1/2 in the
  // density (LeVeque 2002, sec. 8.7); measured 0.62.
  const double rate = std::log(l1[0] / l1[2]) / std::log(spacing[0] / spacing[2]);
  std::printf("  Sod L1 density rate %.2f\n", rate);
  CHECK(rate > 0.5);
}

TEST_CASE("Sod's shock tube with the Wendland C2 kernel", "[sph]") {
  Riemann exact{1.0, 0.0, 1.0, 0.125, 0.0, 0.1, 1.4};
  exact.solve();
  const SodResult r = run_sod(800, exact, kernels::SphKernel::WendlandC2);
  std::printf("  Sod, Wendland C2, %d particles: L1(rho) %.4e, p* %.5f, u* %.5f, shock at %.4f "
              "(exact %.4f), energy drift %.2e\n",
              r.particles, r.l1_density, r.plateau_p, r.plateau_u, r.shock_x, 0.2 * 1.75216,
              r.energy_drift);
  // Measured: p* -1.0%, u* -1.2%, shock 0.0097 behind, L1 8.04e-3 (the cubic spline at this
  // resolution: -1.2%, -1.3%, 0.0098, 8.25e-3).
  CHECK(r.plateau_p == Approx(exact.p_star).epsilon(0.02));
  CHECK(r.plateau_u == Approx(exact.u_star).epsilon(0.02));
  CHECK(std::abs(r.shock_x - 0.2 * 1.75216) < 0.015);
  CHECK(r.l1_density < 0.009);
  CHECK(r.energy_drift < 1e-4);
}

namespace {
/// A 0.1 m slab of TNT (JWL, Dobratz) in n particles, h = 1.5 dx, lit at x = 0; with
/// `unreacted`, the unreacted TNT of problems/sph_tnt_slab.yaml (U_s = 2390 + 2.05 u_p m/s).
sph::Hydro tnt_slab(int n, bool unreacted) {
  sph::Hydro s;
  s.dim = 1;
  sph::Material tnt;
  tnt.name = "tnt";
  materials::JwlExplosive explosive;
  if (unreacted) explosive.unreacted = materials::MieGruneisen{1630.0, 2390.0, 2.05, 1.0};
  tnt.eos = explosive;
  s.materials.push_back(tnt);
  const materials::Jwl& j = explosive.jwl;
  const double dx = 0.1 / n;
  for (int k = 0; k < n; ++k) {
    const double x[3] = {(k + 0.5) * dx, 0, 0};
    add(s, x, dx, j.rho0, j.e0, 1.5 * dx, 0);
  }
  const double at[3] = {0, 0, 0};
  sph::light_from_point(s, at);
  sph::update_state(s);
  return s;
}
} // namespace

TEST_CASE("TNT slab: programmed burn runs at D_CJ and the front obeys the jump conditions",
          "[sph]") {
  // A slab of TNT (JWL, Dobratz) 0.1 m thick, lit at x = 0 and burning by programmed burn at
  // D_CJ = 6930 m/s. At the front, mass and momentum conservation tie the state to the Rayleigh
  // line: rho = rho0 D / (D - u) and p = rho0 D u. The front reaches 17.9 GPa = 0.851 P_CJ at
  // every resolution and burn width tried (400-3200 particles, 0.5-20 h): with a pressureless
  // unreacted explosive the burn completes before the material is compressed to the CJ state,
  // and the products' Hugoniot touches the Rayleigh line only at CJ (see the JWL CJ test).
  // The next test adds the unreacted explosive, whose ZND front ends at P_CJ.
  for (int n : {400, 800}) {
    sph::Hydro s = tnt_slab(n, false);
    const materials::Jwl& j = std::get<materials::JwlExplosive>(s.materials[0].eos).jwl;
    const double L = 0.1, D = j.detonation_speed;
    const double e0 = sph::energies(s).total();
    double t_front[2] = {-1, -1};
    double worst_rayleigh = 0.0, worst_mass = 0.0, peak = 0.0;
    while (s.particles.time < 0.8 * L / D) {
      sph::advance(s, sph::stable_step(s));
      const particles::ParticleSet& P = s.particles;
      const sph::ParticleFields& F = s.fields;
      int arg = 0;
      for (int i = 0; i < P.size(); ++i)
        if (F.p[i] > F.p[arg]) arg = i;
      const double xf = (P.X[3 * arg] + P.u[3 * arg]), u = P.v[3 * arg];
      if (xf > 0.3 * L && xf < 0.75 * L) {
        peak = std::max(peak, F.p[arg]);
        worst_rayleigh = std::max(worst_rayleigh, std::abs(F.p[arg] / (j.rho0 * D * u) - 1.0));
        worst_mass = std::max(worst_mass, std::abs(F.rho[arg] / (j.rho0 * D / (D - u)) - 1.0));
      }
      if (t_front[0] < 0 && xf >= 0.3 * L) t_front[0] = s.particles.time;
      if (t_front[1] < 0 && xf >= 0.7 * L) t_front[1] = s.particles.time;
    }
    const double speed = 0.4 * L / (t_front[1] - t_front[0]);
    const double drift = std::abs(sph::energies(s).total() - e0) / e0;
    std::printf("  TNT slab, %d particles: front speed %.0f m/s (D 6930), peak pressure %.2f GPa "
                "= %.3f P_CJ, Rayleigh line %.2e, mass jump %.2e, energy drift %.2e, %ld steps\n",
                n, speed, peak / 1e9, peak / j.cj_pressure, worst_rayleigh, worst_mass, drift,
                s.particles.step);
    INFO(n << " particles");
    CHECK(speed == Approx(D).epsilon(0.01));
    CHECK(worst_rayleigh < 0.03);
    CHECK(worst_mass < 0.01);
    CHECK(drift < 1e-3);
  }
}

TEST_CASE("a detonation plane lights a 2D TNT strip as a plane wave at D_CJ", "[sph]") {
  // A 40 x 6 mm strip lit by the plane x = 0 (programmed burn, pressureless explosive): every
  // row of particles has the same lighting time at the same x, and the front (the largest
  // pressure of each row) crosses the strip at D_CJ with the rows within one spacing.
  sph::Hydro s;
  s.dim = 2;
  sph::Material tnt;
  tnt.eos = materials::JwlExplosive{};
  s.materials.push_back(tnt);
  const materials::Jwl& j = std::get<materials::JwlExplosive>(tnt.eos).jwl;
  const double dx = 0.5e-3, D = j.detonation_speed;
  const int nx = 80, ny = 12;
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      const double x[3] = {(c + 0.5) * dx, (r + 0.5) * dx, 0};
      add(s, x, dx * dx, j.rho0, j.e0, 1.5 * dx, 0);
    }
  const double at[3] = {0, 0, 0}, normal[3] = {1, 0, 0};
  sph::light_from_plane(s, at, normal);
  for (int i = 0; i < s.particles.size(); ++i)
    REQUIRE(s.fields.light_time[i] == Approx((s.particles.X[3 * i] + s.particles.u[3 * i]) / D));
  sph::update_state(s);
  const auto fronts = [&]() {
    std::vector<double> x(ny, 0.0), p(ny, -1.0);
    for (int i = 0; i < s.particles.size(); ++i) {
      const int r = i / nx;
      if (s.fields.p[i] > p[r])
        p[r] = s.fields.p[i], x[r] = (s.particles.X[3 * i] + s.particles.u[3 * i]);
    }
    return x;
  };
  const double t1 = 0.3 * nx * dx / D, t2 = 0.7 * nx * dx / D;
  while (s.particles.time < t1)
    sph::advance(s, std::min(sph::stable_step(s), t1 - s.particles.time));
  const std::vector<double> x1 = fronts();
  while (s.particles.time < t2)
    sph::advance(s, std::min(sph::stable_step(s), t2 - s.particles.time));
  const std::vector<double> x2 = fronts();
  // The inner rows (two spacings from the free edges, where the products expand sideways).
  double lo = 1e300, hi = -1e300, speed = 0.0;
  for (int r = 2; r < ny - 2; ++r) {
    lo = std::min(lo, x2[r]), hi = std::max(hi, x2[r]);
    speed += (x2[r] - x1[r]) / (t2 - t1) / (ny - 4);
  }
  std::printf("  plane detonation: front speed %.0f m/s (D 6930), rows within %.2f dx\n", speed,
              (hi - lo) / dx);
  CHECK(speed == Approx(D).epsilon(0.02));
  CHECK(hi - lo <= dx * 1.01);
}

TEST_CASE("TNT slab with an unreacted equation of state: a self-sustained ZND front at D_CJ "
          "that ends at the Chapman-Jouguet pressure",
          "[sph]") {
  // The unreacted TNT (Mie-Grueneisen, U_s = 2390 + 2.05 u_p m/s) is lit where the shock has
  // compressed it by 10%; its burn then takes 6 h / D_CJ. Nothing imposes the front speed: it
  // follows from the products' JWL. The state at the end of the burn is the CJ state
  // (P_CJ = 21.0 GPa of the Dobratz constants), ahead of it the von Neumann spike of the
  // unreacted Hugoniot at D, rho0 D (D - c0) / s = 25.0 GPa, smeared by the viscosity.
  for (int n : {400, 800, 1600}) {
    sph::Hydro s = tnt_slab(n, true);
    s.settings.burn_width = 6.0;
    const materials::Jwl& j = std::get<materials::JwlExplosive>(s.materials[0].eos).jwl;
    const double L = 0.1, D = j.detonation_speed;
    double t_front[2] = {-1, -1}, cj_sum = 0.0, spike = 0.0;
    int cj_count = 0;
    while (s.particles.time < 0.85 * L / D) {
      sph::advance(s, sph::stable_step(s));
      const particles::ParticleSet& P = s.particles;
      const sph::ParticleFields& F = s.fields;
      int front = 0;
      for (int i = 0; i < P.size(); ++i)
        if (F.p[i] > F.p[front]) front = i;
      const double xf = (P.X[3 * front] + P.u[3 * front]);
      if (t_front[0] < 0 && xf >= 0.3 * L) t_front[0] = s.particles.time;
      if (t_front[1] < 0 && xf >= 0.7 * L) t_front[1] = s.particles.time;
      if (xf < 0.3 * L || xf > 0.75 * L) continue;
      spike = std::max(spike, F.p[front]);
      // The end of the reaction zone: the first particle behind the front that has burnt.
      for (int i = front; i >= 0; --i) {
        const double burnt =
            (s.particles.time - F.light_time[i]) * D / (s.settings.burn_width * F.h[i]);
        if (F.light_time[i] >= 0.0 && burnt >= 1.0) {
          cj_sum += F.p[i];
          ++cj_count;
          break;
        }
      }
    }
    const double speed = 0.4 * L / (t_front[1] - t_front[0]);
    const double cj = cj_sum / cj_count, vn = j.rho0 * D * (D - 2390.0) / 2.05;
    std::printf("  ZND front, %d particles: speed %.0f m/s (D_CJ 6930), end of burn %.2f GPa = "
                "%.3f P_CJ, peak %.2f GPa (von Neumann %.2f)\n",
                n, speed, cj / 1e9, cj / j.cj_pressure, spike / 1e9, vn / 1e9);
    INFO(n << " particles");
    CHECK(speed == Approx(D).epsilon(0.02));
    CHECK(cj == Approx(j.cj_pressure).epsilon(0.10));
    CHECK(spike == Approx(vn).epsilon(0.10));
  }
}

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
    materials::J2State committed;
    committed.alpha = 0.01;
    const materials::J2Result3D implicit = materials::j2_update_3d(p, strain, committed);
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
  materials::J2State galerkin;
  materials::Vec6 S = materials::Vec6::Zero(), beta = materials::Vec6::Zero();
  double alpha = 0.0, previous = 0.0;
  int plastic_steps = 0;
  for (double level : path) {
    const materials::Vec6 strain = level * direction;
    const materials::J2Result3D implicit = materials::j2_update_3d(p, strain, galerkin);
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
  materials::J2State galerkin;
  double previous = 0.0;
  int plastic_steps = 0;
  for (double level : path) {
    const materials::J2Result3D implicit =
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

TEST_CASE("plane elastic wave in a 2D and a 3D block: stress behind the front", "[sph][solid]") {
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
  const io::ProblemSpec spec = load_problem(
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
  sph::Hydro h = explicit_dynamics::build_sph(*spec.sph);
  REQUIRE(h.loads.size() == 1);
  REQUIRE(h.loads[0].particles.size() == 100);
  const double e0 = sph::energies(h).total();
  double dt_max = 0.0;
  while (h.particles.time < spec.sph->end_time) {
    const double dt = std::min(sph::stable_step(h), spec.sph->end_time - h.particles.time);
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
      s.transmitting.push_back(b);
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
