// SPH started from a preloaded state: the density each solid equation of state gives for a
// pressure, a homogeneous stressed block held at rest by symmetry planes, fixed walls and
// surface forces, particles over their yield surfaces counted and returned, a soil column under
// gravity on a transmitting bottom, the energy balance with gravity, surface forces and damping,
// and the problem-file keys gravity and traction.
#include "meshfree/core/error.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/sph/held_loads.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/initial_state.hpp"
#include "meshfree/sph/state.hpp"
#include "meshfree/sph/step.hpp"
#include "meshfree/sph/support_balance.hpp"
#include "sph_test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <yaml-cpp/yaml.h>

using namespace mf;

namespace {

const double E = 200e9, nu = 0.3, rho0 = 7850.0;
const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));

materials::LinearPolynomial linear_eos(double rho, double bulk) {
  materials::LinearPolynomial eos;
  eos.rho0 = rho;
  eos.c[1] = bulk;
  return eos;
}

sph::Material steel() {
  sph::Material m;
  m.name = "steel";
  m.eos = linear_eos(rho0, K);
  m.strength = materials::ElasticShear{G};
  return m;
}

/// Dry sand: the first points of the compaction curve and granular yield table of
/// problems/sph_tunnel_blast.yaml (Laine & Sandvik 2001; MSB344 Table E:a).
materials::Compaction sand_eos() {
  materials::Compaction c;
  c.loading = {{1674.0, 1739.5, 1873.8, 1997.0}, {0.0, 4.577e6, 14.98e6, 29.15e6}};
  c.sound_speed = {{1674.0, 1746.0, 2086.0}, {265.2, 852.1, 1721.7}};
  c.tensile_limit = 1.0e3;
  return c;
}
materials::GranularStrength sand_strength() {
  materials::GranularStrength g;
  g.yield = {{0.0, 3.40e6, 3.49e7}, {0.0, 4.24e6, 4.47e7}};
  g.shear_modulus = {{0.0}, {7.69e7}};
  return g;
}

/// |p_EOS(rho(p)) - p| relative to |p|, on the loading curve the inversion chose.
template <class Law>
double pressure_back(const Law& law, double p, double e, sph::EosDensity* out = nullptr) {
  const sph::EosDensity d = sph::density_for_pressure(law, p, e);
  if (out) *out = d;
  return std::abs(materials::pressure_and_sound(law, d.rho, e, d.rho_max, 0.0).p - p) / std::abs(p);
}

} // namespace

TEST_CASE("SPH initial state: each solid equation of state gives back the pressure it was "
          "inverted for",
          "[sph][staging]") {
  // Linear (C1 = K): rho = rho0 (1 + p / K) in closed form.
  const materials::LinearPolynomial linear = linear_eos(rho0, K);
  for (const double p : {-5e8, -1e7, -1e6, 1e6, 1e7, 5e8, 5e9}) {
    sph::EosDensity d;
    CHECK(pressure_back(linear, p, 0.0, &d) < 1e-10);
    CHECK(std::abs(d.rho - rho0 * (1.0 + p / K)) < 1e-15 * rho0);
  }
  // The full polynomial with its energy terms, at two energies.
  materials::LinearPolynomial poly = linear_eos(2700.0, 70e9);
  poly.c[2] = 40e9, poly.c[3] = 10e9, poly.c[4] = 1.2, poly.c[5] = 0.8, poly.c[6] = 0.1;
  for (const double e : {0.0, 2e5})
    for (const double p : {-1e9, -1e6, 1e6, 1e9, 2e10}) CHECK(pressure_back(poly, p, e) < 1e-10);
  // Mie-Gruneisen, aluminium (rho0 2785, c0 5328, s 1.338, Gamma0 2.0), in tension and up to
  // 100 GPa on the Hugoniot branch.
  const materials::MieGruneisen mg{2785.0, 5328.0, 1.338, 2.0};
  for (const double e : {0.0, 3e5})
    for (const double p : {-1e9, -1e6, 1e6, 1e9, 3e10, 1e11})
      CHECK(pressure_back(mg, p, e) < 1e-10);
  // Compaction on its loading curve (rho_max = rho), the table's own interpolation in closed
  // form; below zero unloaded from the first point down to the tensile limit.
  const materials::Compaction sand = sand_eos();
  for (const double p : {2e6, 4.577e6, 10e6, 29.15e6}) {
    sph::EosDensity d;
    CHECK(pressure_back(sand, p, 0.0, &d) < 1e-10);
    CHECK(d.rho_max == d.rho);
    const double rho = p <= 4.577e6 ? 1674.0 + p / 4.577e6 * 65.5
                                    : 1739.5 + (p - 4.577e6) / (14.98e6 - 4.577e6) * 134.3;
    if (p <= 14.98e6) CHECK(std::abs(d.rho - rho) < 1e-12 * rho);
  }
  {
    sph::EosDensity d;
    CHECK(pressure_back(sand, -500.0, 0.0, &d) < 1e-10);
    CHECK(d.rho_max == 1674.0);
    CHECK(std::abs(d.rho - (1674.0 - 500.0 / (265.2 * 265.2))) < 1e-12 * 1674.0);
    // Beyond the tensile limit the law's limit is what it can give.
    const sph::EosDensity limit = sph::density_for_pressure(sand, -5e3, 0.0);
    CHECK(materials::compaction(sand_eos(), limit.rho, limit.rho_max).p == Approx(-1e3));
  }
  CHECK_THROWS_AS(sph::density_for_pressure(sand, 40e6, 0.0), Error);
  // HJC (the 1993 paper's concrete): elastic (K = P_crush / mu_crush = 16 GPa), compaction,
  // fully dense, and tension above -T.
  const materials::Hjc hjc;
  for (const double p : {-3e6, 5e6, 16e6, 1e8, 0.8e9, 2e9}) {
    sph::EosDensity d;
    CHECK(pressure_back(hjc, p, 0.0, &d) < 1e-10);
    if (p > 0.0) CHECK(d.rho_max == d.rho);
    if (std::abs(p) < 16e6) CHECK(std::abs(d.rho - hjc.rho0 * (1.0 + p / 16e9)) < 1e-14 * hjc.rho0);
  }
  CHECK_THROWS_AS(sph::density_for_pressure(materials::IdealGas{}, 1e5, 1e5), Error);
  CHECK_THROWS_AS(sph::density_for_pressure(materials::JwlExplosive{}, 1e5, 1e5), Error);
}

namespace {

/// Plane-strain strain of a stress (sxx, syy) with sigma_zz = nu (sxx + syy), no shear.
struct PlaneStrain {
  double exx, eyy;
};
PlaneStrain strain_of(double sxx, double syy) {
  return {(1.0 + nu) / E * ((1.0 - nu) * sxx - nu * syy),
          (1.0 + nu) / E * ((1.0 - nu) * syy - nu * sxx)};
}

enum class Hold { SymmetryAndBalance, WallsAndBalance, TractionOnly };

struct BlockResult {
  double kinetic = 0.0, drift = 0.0, resultant = 0.0;
  bool walls_kept = true;
};

/// A plane-strain steel block [0, n dx]^2 under uniform sxx = -50, syy = -100 MPa, u = eps X,
/// set by set_initial_state. The faces x = 0 and y = 0 are symmetry planes or fixed walls three
/// particles thick carrying the same state; x = L and y = L carry the traction as surface forces
/// (sigma n times the current face length), and with a balance the band within kernel reach of
/// them holds the difference between that and SPH's spread of it.
BlockResult stressed_block(int n, int steps, Hold hold) {
  sph::Hydro h;
  h.dim = 2;
  h.materials.push_back(steel());
  const double dx = 1e-3, L = n * dx;
  const double sxx = -50e6, syy = -100e6, szz = nu * (sxx + syy);
  const PlaneStrain eps = strain_of(sxx, syy);
  const int wall = hold == Hold::WallsAndBalance ? 3 : 0;
  std::vector<int> right, top;
  for (int j = -wall; j < n; ++j)
    for (int i = -wall; i < n; ++i) {
      const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, 0};
      const int k = add(h, x, dx * dx, rho0, 0.0, 1.5 * dx, 0, i < 0 || j < 0);
      if (i == n - 1) right.push_back(k);
      if (j == n - 1) top.push_back(k);
    }
  if (hold != Hold::WallsAndBalance) {
    h.symmetry.push_back({0, 0.0});
    h.symmetry.push_back({1, 0.0});
  }
  const int count = h.particles.size();
  std::vector<double> u(3 * count, 0.0);
  std::vector<sph::Vec6> sigma(count);
  for (int k = 0; k < count; ++k) {
    u[3 * k] = eps.exx * h.particles.X[3 * k];
    u[3 * k + 1] = eps.eyy * h.particles.X[3 * k + 1];
    sigma[k] << sxx, syy, szz, 0, 0, 0;
  }
  sph::set_displacement(h, u);
  const sph::InitialStateReport rep = sph::set_initial_state(h, sigma, {}, {}, false);
  CHECK(rep.over_surface == 0);
  CHECK(rep.density_mismatch < 1e-12);
  // Closed forms: rho = rho0 (1 + p / K), h = 1.5 dx (rho0 / rho)^(1/2), S = sigma + p I.
  const double p = -(sxx + syy + szz) / 3.0, rho = rho0 * (1.0 + p / K);
  const int mid = count / 2;
  CHECK(std::abs(h.fields.rho[mid] - rho) < 1e-14 * rho);
  CHECK(std::abs(h.fields.h[mid] - 1.5 * dx * std::sqrt(rho0 / rho)) < 1e-14 * dx);
  CHECK(std::abs(h.fields.p[mid] - p) < 1e-12 * std::abs(p));
  CHECK(std::abs(h.fields.S[6 * mid + 1] - (syy + p)) < 1e-12 * std::abs(syy));
  CHECK(std::abs(h.fields.S[6 * mid + 2] - (szz + p)) < 1e-12 * std::abs(syy));
  const double tx[3] = {sxx * (1.0 + eps.eyy), 0, 0}, ty[3] = {0, syy * (1.0 + eps.exx), 0};
  h.conditions.add(sph::traction_force(h, "right", right, tx));
  h.conditions.add(sph::traction_force(h, "top", top, ty));
  BlockResult out;
  if (hold != Hold::TractionOnly) {
    std::vector<int> faces = right;
    faces.insert(faces.end(), top.begin(), top.end());
    const sph::SurfaceForce bal = sph::balancing_force(h, "band", sph::within_reach(h, faces));
    double sum[2] = {0, 0};
    for (std::size_t k = 0; k < bal.particles.size(); ++k)
      sum[0] += bal.force[3 * k], sum[1] += bal.force[3 * k + 1];
    out.resultant = std::max(std::abs(sum[0] / (tx[0] * L)), std::abs(sum[1] / (ty[1] * L)));
    h.conditions.add(bal);
  }
  const double W = 0.5 * (sxx * eps.exx + syy * eps.eyy) * L * L;
  for (int s = 0; s < steps; ++s) {
    sph::advance(h, sph::stable_step(h));
    out.kinetic = std::max(out.kinetic, sph::energies(h).kinetic / W);
  }
  double umax = 0.0;
  for (int k = 0; k < count; ++k)
    for (int d = 0; d < 2; ++d) {
      umax = std::max(umax, std::abs(u[3 * k + d]));
      out.drift = std::max(out.drift, std::abs(h.particles.u[3 * k + d] - u[3 * k + d]));
      if (h.fields.fixed[k] &&
          (h.particles.u[3 * k + d] != u[3 * k + d] || h.particles.v[3 * k + d] != 0.0))
        out.walls_kept = false;
    }
  out.drift /= umax;
  std::printf("  block %d x %d (%s): largest kinetic / strain energy %.3e over %d steps, drift "
              "%.3e of the largest displacement; band resultant %.3e of the traction's\n",
              n, n,
              hold == Hold::SymmetryAndBalance ? "symmetry planes"
              : hold == Hold::WallsAndBalance  ? "fixed walls"
                                               : "tractions only",
              out.kinetic, steps, out.drift, out.resultant);
  return out;
}

} // namespace

TEST_CASE("SPH initial state: a homogeneous stressed block held by its boundaries stays at rest",
          "[sph][staging]") {
  // Held by symmetry planes and by fixed walls (which keep the u they were given, bit for bit),
  // with the far faces' tractions and their band balance, the block is in SPH's own equilibrium
  // from the first step: measured kinetic / strain energy 3e-30 and drift 3e-14 over 2,000 steps
  // (rounding); the issue's bound is 1e-6 and 0.1%. The band's balance is what SPH's kernel sums
  // make of a face's traction less the traction itself: its resultant is the quadrature error of
  // the kernel sums at the surface, measured 0.85% of the traction's.
  for (const Hold hold : {Hold::SymmetryAndBalance, Hold::WallsAndBalance}) {
    const BlockResult r = stressed_block(20, 2000, hold);
    CHECK(r.kinetic < 1e-6);
    CHECK(r.drift < 1e-6);
    CHECK(r.resultant < 0.02);
    CHECK(r.walls_kept);
  }
  // The tractions alone on the outer layer leave the two layers behind it out of balance by
  // about 18% of a particle's t A each, in opposite directions: the block rings (measured 2.5e-3
  // of the strain energy within 500 steps).
  CHECK(stressed_block(20, 500, Hold::TractionOnly).kinetic > 1e-4);
}

TEST_CASE("SPH initial state: J2, granular and HJC particles over their yield surfaces are "
          "counted and returned",
          "[sph][staging]") {
  sph::Hydro h;
  h.dim = 2;
  // J2 steel: sigma_y = 250 MPa + 1 GPa alpha (isotropic) and H_kinematic = 0.5 GPa.
  sph::Material j2 = steel();
  materials::VonMises vm;
  vm.shear_modulus = G;
  vm.j2.E = 2.0 * G, vm.j2.nu = 0.0, vm.j2.sigma0 = 250e6;
  vm.j2.hardening = materials::LinearHardening{1e9};
  vm.j2.H_kinematic = 0.5e9;
  j2.strength = vm;
  sph::Material sand;
  sand.name = "sand", sand.eos = sand_eos(), sand.strength = sand_strength();
  sph::Material concrete;
  concrete.name = "concrete", concrete.eos = materials::Hjc{}, concrete.strength = materials::Hjc{};
  h.materials = {j2, sand, concrete};
  const double x[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) add(h, x, 1e-6, rho0, 0.0, 1.5e-3, 0);
  for (int k = 0; k < 2; ++k) add(h, x, 1e-6, 1674.0, 0.0, 1.5e-3, 1);
  add(h, x, 1e-6, 2440.0, 0.0, 1.5e-3, 2);
  // J2: sigma = -p I + beta + xi, xi along a deviatoric unit direction with von Mises r Y,
  // Y = 250 + 1000 x 0.02 = 270 MPa; r = 0.5 (inside), 1 (on), 1.3 (over).
  const double Y = 270e6, p = 100e6;
  materials::Vec6 dir, beta;
  dir << 2, -1, -1, 0, 0, 1;
  dir /= std::sqrt(4.0 + 1.0 + 1.0 + 2.0);
  beta << 20e6, -10e6, -10e6, 0, 0, 5e6;
  const materials::Vec6 I = (materials::Vec6() << 1, 1, 1, 0, 0, 0).finished();
  std::vector<sph::Vec6> sigma(6);
  const double ratios[3] = {0.5, 1.0, 1.3};
  for (int k = 0; k < 3; ++k) sigma[k] = -p * I + beta + ratios[k] * std::sqrt(2.0 / 3.0) * Y * dir;
  // Granular sand at p = 10 MPa: Y(p) by the table, q = Y / 2 and 2 Y.
  const double ps = 10e6;
  const double Ys = 4.24e6 + (ps - 3.4e6) / (3.49e7 - 3.4e6) * (4.47e7 - 4.24e6);
  sigma[3] = -ps * I + 0.5 * std::sqrt(2.0 / 3.0) * Ys * dir;
  sigma[4] = -ps * I + 2.0 * std::sqrt(2.0 / 3.0) * Ys * dir;
  // HJC at p = 20 MPa: Y = fc (A + B (p / fc)^N) at the static rate, q = 1.5 Y.
  const materials::Hjc c;
  const double pc = 20e6, Yc = c.fc * (c.A + c.B * std::pow(pc / c.fc, c.N));
  sigma[5] = -pc * I + 1.5 * std::sqrt(2.0 / 3.0) * Yc * dir;
  std::vector<sph::Vec6> back(6, sph::Vec6::Zero());
  for (int k = 0; k < 3; ++k) back[k] = beta;
  const std::vector<double> alpha = {0.02, 0.02, 0.02, 0.0, 0.0, 0.0};
  for (const bool ret : {false, true}) {
    const sph::InitialStateReport r = sph::set_initial_state(h, sigma, alpha, back, ret);
    CHECK(r.over_surface == 3);
    CHECK(r.on_surface == 1);
    CHECK(r.returned == (ret ? 3 : 0));
    CHECK(r.worst_particle == 4);
    CHECK(std::abs(r.worst_ratio - 2.0) < 1e-9);
    CHECK(r.density_mismatch < 1e-12);
    const auto q = [&](int i, bool about_beta) {
      materials::Vec6 s;
      for (int k = 0; k < 6; ++k)
        s(k) = h.fields.S[6 * i + k] - (about_beta ? h.fields.back_stress[6 * i + k] : 0.0);
      return materials::von_mises_3d(s);
    };
    const double over[3] = {q(2, true) / Y, q(4, false) / Ys, q(5, false) / Yc};
    const double expect[3] = {ret ? 1.0 : 1.3, ret ? 1.0 : 2.0, ret ? 1.0 : 1.5};
    for (int k = 0; k < 3; ++k) CHECK(std::abs(over[k] - expect[k]) < 1e-10);
    CHECK(std::abs(q(0, true) / Y - 0.5) < 1e-12);
    // The radial return keeps the history and the direction: S - beta = xi / 1.3 for J2.
    CHECK(h.fields.alpha[2] == 0.02);
    for (int k = 0; k < 6; ++k) {
      CHECK(h.fields.back_stress[6 * 2 + k] == beta(k));
      const double xi = (ret ? 1.0 : 1.3) * std::sqrt(2.0 / 3.0) * Y * dir(k);
      CHECK(std::abs(h.fields.S[6 * 2 + k] - h.fields.back_stress[6 * 2 + k] - xi) < 1e-9 * Y);
    }
    for (int i = 0; i < 6; ++i) CHECK((h.fields.damage[i] == 0.0 && h.fields.failed[i] == 0));
  }
}

namespace {

struct ColumnResult {
  double settle_peak = 0.0, kinetic = 0.0, drift = 0.0, stress_error = 0.0;
};

/// A soil column (elastic, E 100 MPa, nu 0.25, rho 2000 kg/m^3; 6 x 40 particles of 0.25 m,
/// 10 m high) on a transmitting bottom, rollers (symmetry planes) on its sides, gravity 9.81,
/// the geostatic state sigma_yy = -rho g (H - y), sigma_xx = sigma_zz = K0 sigma_yy with
/// K0 = nu / (1 - nu) (uniaxial strain) and u_y = -rho g (H y - y^2 / 2) / M, M = K + 4G/3. The
/// bottom holds sigma . n A beside its dashpots, and its band the balance with the body's
/// resultant. `settle` steps with damping c, then `quiet` steps without.
ColumnResult column(int settle, double c, int quiet) {
  const double Es = 100e6, nus = 0.25, rs = 2000.0, g = 9.81, dx = 0.25;
  const double Ks = Es / (3.0 * (1.0 - 2.0 * nus)), Gs = Es / (2.0 * (1.0 + nus));
  const double M = Ks + 4.0 / 3.0 * Gs, K0 = nus / (1.0 - nus);
  const int cols = 6, rows = 40;
  const double H = rows * dx;
  sph::Hydro h;
  h.dim = 2;
  sph::Material soil;
  soil.name = "soil", soil.eos = linear_eos(rs, Ks), soil.strength = materials::ElasticShear{Gs};
  h.materials.push_back(soil);
  std::vector<int> bottom;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, 0};
      const int k = add(h, x, dx * dx, rs, 0.0, 1.5 * dx, 0);
      if (j == 0) bottom.push_back(k);
    }
  h.symmetry.push_back({0, 0.0});
  h.symmetry.push_back({0, cols * dx});
  h.body.gravity[1] = -g;
  const int n = h.particles.size();
  std::vector<sph::Vec6> sigma(n);
  std::vector<double> u(3 * n, 0.0);
  for (int k = 0; k < n; ++k) {
    const double y = h.particles.X[3 * k + 1], syy = -rs * g * (H - y);
    sigma[k] << K0 * syy, syy, K0 * syy, 0, 0, 0;
    u[3 * k + 1] = -rs * g * (H * y - 0.5 * y * y) / M;
  }
  sph::set_displacement(h, u);
  CHECK(sph::set_initial_state(h, sigma, {}, {}, false).density_mismatch < 1e-12);
  sph::TransmittingBoundary b;
  b.name = "bottom", b.particles = bottom, b.normal[1] = -1.0;
  for (const int i : bottom) {
    b.area.push_back(sph::face_area(h.particles, i, 2));
    b.normal_impedance.push_back(h.fields.rho[i] * h.fields.c[i]);
    b.shear_impedance.push_back(std::sqrt(h.fields.rho[i] * Gs));
  }
  sph::hold_stress(b, sigma);
  // The static force is the column's weight above the layer's centre, per face.
  CHECK(std::abs(b.static_force[1] - rs * g * (H - 0.5 * dx) * dx) < 1e-12 * rs * g * H * dx);
  h.conditions.add(b);
  h.conditions.add(sph::balancing_force(h, "bottom_band", sph::within_reach(h, bottom), true));
  const double W = cols * dx * std::pow(rs * g, 2) * std::pow(H, 3) / (6.0 * M);
  ColumnResult out;
  h.body.damping = c;
  for (int s = 0; s < settle; ++s) {
    sph::advance(h, sph::stable_step(h));
    out.settle_peak = std::max(out.settle_peak, sph::energies(h).kinetic / W);
  }
  h.body.damping = 0.0;
  for (int s = 0; s < quiet; ++s) {
    sph::advance(h, sph::stable_step(h));
    out.kinetic = std::max(out.kinetic, sph::energies(h).kinetic / W);
  }
  double umax = 0.0;
  for (int k = 0; k < n; ++k) {
    umax = std::max(umax, std::abs(u[3 * k + 1]));
    out.drift = std::max(out.drift, std::abs(h.particles.u[3 * k + 1] - u[3 * k + 1]));
    // sigma_yy = S_yy - p against rho g (H - y), below the top three rows.
    if (h.particles.X[3 * k + 1] < H - 3 * dx)
      out.stress_error =
          std::max(out.stress_error,
                   std::abs(h.fields.S[6 * k + 1] - h.fields.p[k] - sigma[k](1)) / (rs * g * H));
  }
  out.drift /= umax;
  std::printf("  column: kinetic / strain energy %.3e at most while settling (%d steps, c = %.0f "
              "/s), %.3e at most over %d steps after; drift %.3e of the largest displacement, "
              "sigma_yy within %.3e of rho g H\n",
              out.settle_peak, settle, c, out.kinetic, quiet, out.drift, out.stress_error);
  return out;
}

} // namespace

TEST_CASE("SPH initial state: a geostatic soil column on a transmitting bottom is quiet after a "
          "short damped settle",
          "[sph][staging]") {
  // The column starts in SPH's balance except for the top rows, whose free surface carries the
  // stress at the particles' centres (an O(h) error): undamped, that rings at 1.7e-5 of the
  // strain energy (measured). A settle of 300 steps (0.14 s, 0.85 of the first period
  // 4H / c_p = 0.163 s) with c = 2 omega_1 = 77 /s (critical for the first mode) takes the
  // underdamped rest down by about exp(-c t) = 2.4e-5, to ~4e-10; measured 1.8e-9 over the
  // 1,000 undamped steps after. Bound: 1e-8. The free top pushes its rows up with the stress
  // at their centres, rho g dx / 2 where it should be 0, and the bottom band takes that
  // resultant: the column settles with sigma_yy off by at most that, dx / (2H) = 1.25% of
  // rho g H (measured 0.69%, largest near the bottom), and its particles move by 0.39% of the
  // largest displacement (bound 1%).
  const ColumnResult r = column(300, 77.0, 1000);
  CHECK(r.kinetic < 1e-8);
  CHECK(r.drift < 0.01);
  CHECK(r.stress_error < 0.0125);
}

TEST_CASE("SPH: gravity, constant surface forces and damping do the work the energy balance "
          "counts",
          "[sph][staging]") {
  // A free plane-strain steel block (10 x 10 particles of 1 mm, no support) under gravity
  // (scaled to 1e5 m/s^2 so that it matters within the run) and a 20 MPa traction on its right
  // face. No internal force has a resultant (pairwise antisymmetric sums), so the momentum is
  // (M g + F) t to rounding; the energy changes by the counted work of gravity and the forces,
  // and with damping on, by the damping's (negative) work as well. The balance is left with the
  // step's own error in the internal energy: measured 1.9e-5 and 3.2e-5 of the work (bound
  // 1e-3).
  for (const double c : {0.0, 2e4}) {
    sph::Hydro h;
    h.dim = 2;
    h.materials.push_back(steel());
    const double dx = 1e-3;
    std::vector<int> right;
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, 0};
        const int k = add(h, x, dx * dx, rho0, 0.0, 1.5 * dx, 0);
        if (i == 9) right.push_back(k);
      }
    h.body.gravity[1] = -1e5;
    h.body.damping = c;
    const double t[3] = {20e6, 0, 0};
    h.conditions.add(sph::traction_force(h, "pull", right, t));
    sph::update_state(h);
    const double e0 = sph::energies(h).total(), mass = rho0 * 100 * dx * dx;
    const double F = 20e6 * 10 * dx;
    for (int s = 0; s < 400; ++s) sph::advance(h, sph::stable_step(h));
    const sph::Energies En = sph::energies(h);
    const double balance = std::abs(En.total() - e0 - h.external_work);
    double px = 0.0, py = 0.0;
    for (int i = 0; i < h.particles.size(); ++i)
      px += h.particles.mass[i] * h.particles.v[3 * i],
          py += h.particles.mass[i] * h.particles.v[3 * i + 1];
    const double time = h.particles.time;
    std::printf("  free block, damping %.0f /s: |E - E0 - W| %.3e of W = %.4e J (damping's part "
                "%.4e J); momentum (%.6e, %.6e) against (F t, M g t) = (%.6e, %.6e)\n",
                c, balance / std::abs(h.external_work), h.external_work, h.damping_work, px, py,
                F * time, -mass * 1e5 * time);
    CHECK(balance < 1e-3 * std::abs(h.external_work));
    if (c == 0.0) {
      CHECK(h.damping_work == 0.0);
      CHECK(std::abs(px - F * time) < 1e-12 * F * time);
      CHECK(std::abs(py + mass * 1e5 * time) < 1e-12 * mass * 1e5 * time);
    } else {
      // dP/dt = F_ext - c P: P = F_ext (1 - exp(-c t)) / c, which the midpoint step follows to
      // O((c dt)^2) = 2e-6.
      CHECK(h.damping_work < 0.0);
      const double decay = (1.0 - std::exp(-c * time)) / c;
      CHECK(std::abs(px - F * decay) < 1e-5 * F * decay);
      CHECK(std::abs(py + mass * 1e5 * decay) < 1e-5 * mass * 1e5 * decay);
    }
  }
}

TEST_CASE("SPH problem keys: gravity and a boundary traction", "[sph][staging]") {
  const char* problem = R"(
name: held
units: N, m, kg, s
analysis: sph
model: {type: plane_strain}
materials:
  - name: steel
    eos: {type: linear_polynomial, rho0: 7850, c: [0, 166.7e9, 0, 0, 0, 0, 0]}
    shear_modulus: 76.9e9
regions:
  - {material: steel, box: [[0, 0], [0.01, 0.01]], spacing: 0.001, density: 7850, energy: 0}
gravity: [0, -9.81]
boundary:
  - {name: pull, box: [[0.0095, 0], [0.0105, 0.01]], traction: [1.0e6, -2.0e5]}
time: {end: 1.0e-6}
)";
  const spec::ProblemSpec spec = spec::parse_problem(YAML::Load(problem));
  const sph::Hydro h = explicit_dynamics::build_sph(spec.sph());
  CHECK(h.body.gravity[0] == 0.0);
  CHECK(h.body.gravity[1] == -9.81);
  REQUIRE(h.conditions.size() == 1);
  REQUIRE(h.conditions.of_kind<sph::SurfaceForce>().size() == 1);
  const sph::SurfaceForce& f = *h.conditions.of_kind<sph::SurfaceForce>()[0];
  CHECK(f.name == "pull");
  CHECK(f.particles.size() == 10);
  for (std::size_t k = 0; k < f.particles.size(); ++k) {
    CHECK(h.particles.X[3 * f.particles[k]] == Approx(0.0095));
    // Traction times the face area V / spacing = 1 mm per unit thickness.
    CHECK(std::abs(f.force[3 * k] - 1.0e3) < 1e-9);
    CHECK(std::abs(f.force[3 * k + 1] + 2.0e2) < 1e-9);
  }
  const auto error_of = [&](const char* key, const char* value) {
    YAML::Node root = YAML::Load(problem);
    if (std::string(key) == "gravity")
      root["gravity"] = YAML::Load(value);
    else
      root["boundary"][0]["traction"] = YAML::Load(value);
    try {
      spec::parse_problem(root);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of("gravity", "[0, -9.81, 1]"), Catch::Contains("gravity"));
  CHECK_THAT(error_of("traction", "[1.0e6]"), Catch::Contains("boundary[0].traction"));
}
