// SPH kernels (unit integral, consistent slopes) and the equations of state against the jump
// conditions they must satisfy and the Chapman-Jouguet point of JWL TNT.
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
      // The profile (W without its normalisation) gives W's ratios: the artificial stress's
      // f = W(r) / W(dp) from one division.
      const kernels::SphKernel k = kind.W == kernels::cubic_spline ? kernels::SphKernel::CubicSpline
                                                                   : kernels::SphKernel::WendlandC2;
      for (double r : {0.0, 0.1, 0.5, 0.69, 0.71, 1.0, 1.3, 1.4, 1.5})
        for (double dp : {0.3, 0.7, 1.1}) {
          const double ratio = kernels::sph_kernel_profile(k, dim, r / h) /
                               kernels::sph_kernel_profile(k, dim, dp / h);
          CHECK(ratio == Approx(kind.W(dim, r, h) / kind.W(dim, dp, h)).epsilon(1e-14).margin(0));
        }
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
