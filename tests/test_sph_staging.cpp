// SPH started from a preloaded state: the density from each equation of state for a given
// pressure, a homogeneous stressed block held at rest, a column under gravity on a transmitting
// boundary, and the energy balance with gravity and constant surface forces.
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/strength.hpp"
#include "meshfree/sph/held_loads.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/initial_state.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
#include "meshfree/sph/step.hpp"
#include "sph_test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

using namespace mf;

namespace {

const double E = 200e9, nu = 0.3, rho0 = 7850.0;
const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));

sph::Material steel() {
  sph::Material m;
  m.name = "steel";
  materials::LinearPolynomial eos;
  eos.rho0 = rho0;
  eos.c[1] = K;
  m.eos = eos;
  m.strength = materials::ElasticShear{G};
  return m;
}

/// Plane-strain strain of a stress (sxx, syy, sxy) with sigma_zz = nu (sxx + syy).
struct PlaneStrain {
  double exx, eyy, gxy;
};
PlaneStrain strain_of(double sxx, double syy, double sxy) {
  return {(1.0 + nu) / E * ((1.0 - nu) * sxx - nu * syy),
          (1.0 + nu) / E * ((1.0 - nu) * syy - nu * sxx), sxy / G};
}

struct BlockResult {
  double kinetic_ratio = 0.0, drift = 0.0;
};

/// A plane-strain block [0, n dx]^2 under uniform (sxx, syy), symmetry planes on x = 0 and
/// y = 0, the other two faces held by `mode`: 0 tractions as forces on the face layer.
BlockResult stressed_block(int n, int steps, int mode) {
  sph::Hydro h;
  h.dim = 2;
  h.materials.push_back(steel());
  const double dx = 1e-3, L = n * dx;
  const double sxx = -50e6, syy = -100e6, szz = nu * (sxx + syy);
  const PlaneStrain eps = strain_of(sxx, syy, 0.0);
  std::vector<int> right, top;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, 0};
      const int k = add(h, x, dx * dx, rho0, 0.0, 1.5 * dx, 0);
      if (i == n - 1) right.push_back(k);
      if (j == n - 1) top.push_back(k);
    }
  h.symmetry.push_back({0, 0.0});
  h.symmetry.push_back({1, 0.0});
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
  const double tx[3] = {sxx * (1.0 + eps.eyy), 0, 0}, ty[3] = {0, syy * (1.0 + eps.exx), 0};
  if (mode <= 1) {
    h.forces.push_back(sph::traction_force(h, "right", right, tx));
    h.forces.push_back(sph::traction_force(h, "top", top, ty));
  }
  if (mode == 1) {
    std::vector<int> faces = right;
    faces.insert(faces.end(), top.begin(), top.end());
    const std::vector<int> band = sph::within_reach(h, faces);
    const sph::SurfaceForce bal = sph::balancing_force(h, "balance", band);
    double sum[2] = {0, 0}, biggest = 0;
    for (std::size_t k = 0; k < bal.particles.size(); ++k) {
      sum[0] += bal.force[3 * k], sum[1] += bal.force[3 * k + 1];
      biggest = std::max(biggest, std::hypot(bal.force[3 * k], bal.force[3 * k + 1]));
    }
    std::printf("  band %zu particles, balancing resultant (%.4e, %.4e) of traction resultants "
                "(%.4e, %.4e), largest %.4e\n",
                band.size(), sum[0], sum[1], tx[0] * L, ty[1] * L, biggest);
    h.forces.push_back(bal);
    // per column of the right face
    for (int c = n - 5; c < n; ++c) {
      const int k = (n / 2) * n + c;
      const std::vector<double> f = sph::out_of_balance(h);
      std::printf("   column %d: internal+held fx %.4e\n", c, f[3 * k]);
    }
  }
  const double W = 0.5 * (sxx * eps.exx + syy * eps.eyy) * L * L;
  BlockResult out;
  for (int s = 0; s < steps; ++s) {
    sph::advance(h, sph::stable_step(h));
    out.kinetic_ratio = std::max(out.kinetic_ratio, sph::energies(h).kinetic / W);
  }
  double umax = 0.0, drift = 0.0;
  for (int k = 0; k < count; ++k)
    for (int d = 0; d < 2; ++d) {
      umax = std::max(umax, std::abs(u[3 * k + d]));
      drift = std::max(drift, std::abs(h.particles.u[3 * k + d] - u[3 * k + d]));
    }
  out.drift = drift / umax;
  std::printf("  block %d x %d, mode %d: largest kinetic / strain energy %.3e, drift %.3e of the "
              "largest displacement\n",
              n, n, mode, out.kinetic_ratio, out.drift);
  return out;
}

/// A soil column (elastic, E 100 MPa, nu 0.25, rho 2000) of height H on a transmitting bottom,
/// rollers (symmetry planes) at its sides, geostatic stress sigma_yy = -rho g (H - y),
/// sigma_xx = sigma_zz = K0 sigma_yy, K0 = nu / (1 - nu) (uniaxial strain).
struct ColumnResult {
  double first_ratio = 0.0, settled_ratio = 0.0, drift = 0.0;
};
ColumnResult column(int cols, int rows, int settle, int quiet, double damping, bool balance) {
  const double Es = 100e6, nus = 0.25, rs = 2000.0, g = 9.81, dx = 0.25;
  const double Ks = Es / (3.0 * (1.0 - 2.0 * nus)), Gs = Es / (2.0 * (1.0 + nus));
  const double M = Ks + 4.0 / 3.0 * Gs, K0 = nus / (1.0 - nus), H = rows * dx;
  sph::Hydro h;
  h.dim = 2;
  sph::Material soil;
  soil.name = "soil";
  materials::LinearPolynomial eos;
  eos.rho0 = rs;
  eos.c[1] = Ks;
  soil.eos = eos;
  soil.strength = materials::ElasticShear{Gs};
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
  h.gravity[1] = -g;
  const int n = h.particles.size();
  std::vector<sph::Vec6> sigma(n);
  std::vector<double> u(3 * n, 0.0);
  for (int k = 0; k < n; ++k) {
    const double y = h.particles.X[3 * k + 1];
    const double syy = -rs * g * (H - y);
    sigma[k] << K0 * syy, syy, K0 * syy, 0, 0, 0;
    // u_y = int_0^y sigma_yy / M: the bottom held at u = 0.
    u[3 * k + 1] = -rs * g * (H * y - 0.5 * y * y) / M;
  }
  sph::set_displacement(h, u);
  const sph::InitialStateReport rep = sph::set_initial_state(h, sigma, {}, {}, false);
  CHECK(rep.density_mismatch < 1e-12);
  sph::update_state(h);
  sph::TransmittingBoundary b;
  b.name = "bottom";
  b.particles = bottom;
  b.normal[1] = -1.0;
  for (const int i : bottom) {
    b.area.push_back(sph::face_area(h.particles, i, 2));
    b.normal_impedance.push_back(h.fields.rho[i] * h.fields.c[i]);
    b.shear_impedance.push_back(std::sqrt(h.fields.rho[i] * Gs));
  }
  sph::hold_stress(b, sigma);
  h.transmitting.push_back(b);
  const double W = cols * dx * std::pow(rs * g, 2) * std::pow(H, 3) / (6.0 * M);
  const std::vector<double> f0 = sph::out_of_balance(h);
  double worst = 0.0;
  for (int k = 0; k < n; ++k) worst = std::max(worst, std::hypot(f0[3 * k], f0[3 * k + 1]));
  std::printf("  column: initial out-of-balance %.3e of a particle's weight\n",
              worst / (rs * dx * dx * g));
  if (balance) {
    const std::vector<int> band = sph::within_reach(h, bottom);
    h.forces.push_back(sph::balancing_force(h, "bottom_band", band, true));
    const std::vector<double> f1 = sph::out_of_balance(h);
    worst = 0.0;
    for (int k = 0; k < n; ++k) worst = std::max(worst, std::hypot(f1[3 * k], f1[3 * k + 1]));
    std::printf("  column: with the bottom band balanced %.3e\n", worst / (rs * dx * dx * g));
  }
  ColumnResult out;
  h.damping = damping;
  for (int s = 0; s < settle; ++s) {
    sph::advance(h, sph::stable_step(h));
    out.first_ratio = std::max(out.first_ratio, sph::energies(h).kinetic / W);
  }
  h.damping = 0.0;
  const std::vector<double> u_settled = h.particles.u;
  for (int s = 0; s < quiet; ++s) {
    sph::advance(h, sph::stable_step(h));
    out.settled_ratio = std::max(out.settled_ratio, sph::energies(h).kinetic / W);
    if (s % 100 == 0) {
      int worst_k = 0; double dmax = 0;
      for (int k = 0; k < n; ++k) { const double dd = std::abs(h.particles.u[3*k+1] - u[3*k+1]) + std::abs(h.particles.u[3*k]); if (dd > dmax) dmax = dd, worst_k = k; }
      double mv[2] = {0, 0};
      for (int k = 0; k < n; ++k) mv[0] += h.particles.v[3*k], mv[1] += h.particles.v[3*k+1];
      std::printf("   mean v %.3e %.3e\n", mv[0]/n, mv[1]/n);
      std::printf("   step %d t %.4f KE/W %.3e worst drift %.3e at particle %d (x %.3f y %.3f)\n", s, h.particles.time, sph::energies(h).kinetic / W, dmax, worst_k, h.particles.X[3*worst_k], h.particles.X[3*worst_k+1]);
    }
  }
  double umax = 0.0, drift = 0.0;
  for (int k = 0; k < n; ++k) {
    umax = std::max(umax, std::abs(u[3 * k + 1]));
    drift = std::max(drift, std::abs(h.particles.u[3 * k + 1] - u[3 * k + 1]));
  }
  out.drift = drift / umax;
  std::printf("  column %d x %d: kinetic / strain energy %.3e while settling (%d steps, c = "
              "%.1f/s), %.3e over %d steps after; drift %.3e of the largest displacement\n",
              cols, rows, out.first_ratio, settle, damping, out.settled_ratio, quiet, out.drift);
  return out;
}

} // namespace

TEST_CASE("column", "[sph][staging][col]") {
  column(6, 40, 0, 1000, 0.0, true);
  column(6, 40, 300, 1000, 77.0, true);
  column(6, 40, 1000, 1000, 77.0, true);
}

TEST_CASE("a homogeneous stressed SPH block stays at rest", "[sph][staging]") {
  stressed_block(20, 2000, 0);
  stressed_block(20, 2000, 1);
}
