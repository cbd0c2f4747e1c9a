// SPH gas dynamics: Sod's shock tube against the exact Riemann solution, TNT slab and strip
// detonations against the Chapman-Jouguet state, a ZND front with an unreacted equation of state.
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/loads/blast.hpp"
#include "meshfree/materials/eos.hpp"
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/spec/problem_spec.hpp"
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
#include <functional>
#include <limits>

using namespace mf;

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

/// Sod's tube `s` (its gas particles first, in order along x, then its fixed walls) run to
/// t = 0.2 (`each_step` after every step), measured against `exact`.
SodResult run_sod_to_end(sph::Hydro& s, const Riemann& exact,
                         const std::function<void(const sph::Hydro&)>& each_step = {}) {
  const double e0 = sph::energies(s).total();
  while (s.particles.time < 0.2) {
    const double dt = std::min(sph::stable_step(s), 0.2 - s.particles.time);
    sph::advance(s, dt);
    if (each_step) each_step(s);
  }
  const particles::ParticleSet& P = s.particles;
  const sph::ParticleFields& F = s.fields;
  const int n_gas = static_cast<int>(std::count(F.fixed.begin(), F.fixed.end(), 0));
  SodResult out;
  out.particles = n_gas;
  out.energy_drift = std::abs(sph::energies(s).total() - e0) / e0;
  int count = 0, plateau = 0;
  const double rho_mid = 0.5 * (0.26557 + 0.125);
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
  return run_sod_to_end(s, exact);
}

/// The largest and the median number of particles a particle of `s` interacts with (within
/// h_i + h_j of it), from its neighbour list.
std::pair<int, int> interacting_partners(const sph::Hydro& s) {
  const particles::ParticleSet& P = s.particles;
  const sph::ParticleFields& F = s.fields;
  std::vector<int> counts;
  for (int i = 0; i < P.owned_count(); ++i) {
    int n = 0;
    for (long k = s.neighbours.pairs.offset[i]; k < s.neighbours.pairs.offset[i + 1]; ++k) {
      const int j = s.neighbours.pairs.partner[k];
      n += std::abs(P.X[3 * i] + P.u[3 * i] - P.X[3 * j] - P.u[3 * j]) < F.h[i] + F.h[j];
    }
    counts.push_back(n);
  }
  std::sort(counts.begin(), counts.end());
  return {counts.back(), counts[counts.size() / 2]};
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

TEST_CASE("Sod's tube from its problem file: h within its bounds, no particle paired with the "
          "tube, the exact solution's plateau",
          "[sph]") {
  Riemann exact{1.0, 0.0, 1.0, 0.125, 0.0, 0.1, 1.4};
  exact.solve();
  const spec::ProblemSpec spec = load_problem("sph_sod_tube");
  REQUIRE(spec.sph().smoothing_bounds.max == 3.0); // the default in 1D
  for (const bool bounded : {true, false}) {
    sph::Hydro s = explicit_dynamics::build_sph(spec.sph());
    if (!bounded) // as before the bounds: h follows the density wherever it goes
      for (int i = 0; i < s.particles.size(); ++i)
        s.fields.rho_lo[i] = 0.0, s.fields.rho_hi[i] = std::numeric_limits<double>::infinity();
    double largest_h = 0.0;   // over h_ref, over every step
    int most = 0, median = 0; // partners: the largest over every step, the median then
    const SodResult r = run_sod_to_end(s, exact, [&](const sph::Hydro& h) {
      for (int i = 0; i < h.particles.size(); ++i)
        largest_h = std::max(largest_h, h.fields.h[i] / h.fields.h_ref[i]);
      const auto [m, med] = interacting_partners(h);
      if (m > most) most = m, median = med;
    });
    const auto [most_at_end, median_at_end] = interacting_partners(s);
    std::printf("  Sod from its problem file, %s: L1(rho) %.4e, p* %.5f, u* %.5f, shock at %.4f, "
                "largest h / h0 %.4g, most partners %d (median %d then), at t = 0.2 %d (median "
                "%d), h held %ld particle-steps\n",
                bounded ? "bounded h" : "h unbounded", r.l1_density, r.plateau_p, r.plateau_u,
                r.shock_x, largest_h, most, median, most_at_end, median_at_end, s.bounded_h.at_max);
    INFO((bounded ? "bounded" : "unbounded"));
    if (!bounded) {
      // Measured: the first particle of the light gas, thrown ahead of the shock, reaches
      // h = 14,500 h0 and pairs with every particle of the tube (1,807).
      CHECK(largest_h > 1000.0);
      CHECK(most_at_end > 100 * median_at_end);
      continue;
    }
    // Measured: largest h 3.00 h0, held at the bound 193 particle-steps; at t = 0.2 at most 11
    // partners (median 5). The first particle of the light gas (h0 = 8 times its left
    // neighbours') starts with 12 and reaches its bound among the dense gas within 20 steps: 36
    // partners until the contact has spread (t < 0.05), the most the bound lets it take. L1
    // 6.32e-3 (5.66e-3 unbounded, whose thrown particle leaves the measured window), p* -0.45%,
    // u* -0.89%, the shock 0.0017 ahead (0.0067 behind unbounded).
    CHECK(largest_h <= 3.0 * (1 + 1e-12));
    CHECK(most_at_end <= 3 * median_at_end);
    CHECK(most <= 40);
    CHECK(s.bounded_h.at_max > 0);
    CHECK(s.bounded_h.at_min == 0);
    CHECK(r.l1_density < 6.5e-3);
    CHECK(std::abs(r.plateau_p / exact.p_star - 1.0) < 0.01);
    CHECK(std::abs(r.plateau_u / exact.u_star - 1.0) < 0.01);
    CHECK(std::abs(r.shock_x - 0.2 * 1.75216) < 0.01);
    CHECK(r.energy_drift < 1e-4);
  }
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
          "[sph][long]") {
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
