#include "meshfree/sph/initial_state.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/state.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

namespace mf::sph {

namespace {

constexpr double kSqrt23 = 0.81649658092772603273; // sqrt(2/3)

/// The root of an increasing function f on (0, upper): a bracket grown from rho_ref, then
/// Newton steps with a central-difference slope, bisection where a step leaves the bracket,
/// until the bracket or the step reaches the last bits of rho.
template <class F>
double increasing_root(const F& f, double rho_ref, double upper, const char* law) {
  double lo = rho_ref, hi = rho_ref;
  double f_lo = f(lo), f_hi = f_lo;
  if (f_lo == 0.0) return rho_ref;
  double grow = 1e-3;
  for (int k = 0; k < 200 && (f_lo > 0.0) == (f_hi > 0.0); ++k, grow *= 2.0) {
    if (f_lo > 0.0) {
      hi = lo, f_hi = f_lo;
      lo = lo / (1.0 + grow);
      f_lo = f(lo);
    } else {
      lo = hi, f_lo = f_hi;
      // Towards a singular compression (Mie-Gruneisen's 1 / (s - 1)) by halves of the gap.
      hi = std::min(hi * (1.0 + grow), 0.5 * (hi + upper));
      f_hi = f(hi);
    }
  }
  if ((f_lo > 0.0) == (f_hi > 0.0))
    fail("SPH initial state: the ", law,
         " equation of state reaches no density for the pressure "
         "asked (searched from ",
         lo, " to ", hi, ")");
  double x = lo - f_lo * (hi - lo) / (f_hi - f_lo);
  if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
  double best = x, f_best = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 200; ++it) {
    const double fx = f(x);
    if (std::abs(fx) < f_best) best = x, f_best = std::abs(fx);
    if (fx == 0.0) break;
    (fx < 0.0 ? lo : hi) = x;
    if (hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * hi) break;
    const double d = 1e-7 * x;
    const double slope = (f(x + d) - f(x - d)) / (2.0 * d);
    double next = slope > 0.0 ? x - fx / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == x) break;
    x = next;
  }
  for (const double edge : {lo, hi})
    if (std::abs(f(edge)) < f_best) best = edge, f_best = std::abs(f(edge));
  return best;
}

EosDensity invert(const materials::IdealGas&, double, double) {
  fail("SPH initial state: an ideal gas has no solid state to give a stress");
}
EosDensity invert(const materials::JwlExplosive&, double, double) {
  fail("SPH initial state: JWL detonation products have no solid state to give a stress");
}

EosDensity invert(const materials::LinearPolynomial& l, double p, double e) {
  const double rho =
      increasing_root([&](double r) { return materials::linear_polynomial(l, r, e).p - p; }, l.rho0,
                      std::numeric_limits<double>::infinity(), "linear polynomial");
  return {rho, rho};
}

EosDensity invert(const materials::MieGruneisen& m, double p, double e) {
  // The Hugoniot's compression is bounded by mu < 1 / (s - 1).
  const double upper =
      m.s > 1.0 ? m.rho0 * (1.0 + 1.0 / (m.s - 1.0)) : std::numeric_limits<double>::infinity();
  const double rho =
      increasing_root([&](double r) { return materials::mie_gruneisen(m, r, e).p - p; }, m.rho0,
                      upper, "Mie-Gruneisen");
  return {rho, rho};
}

EosDensity invert(const materials::Compaction& c, double p, double) {
  const std::vector<double>& x = c.loading.x;
  const std::vector<double>& y = c.loading.y;
  if (p > y.back())
    fail("SPH initial state: pressure ", p, " is above the top of the compaction curve (", y.back(),
         " at density ", x.back(), ")");
  if (p < y.front()) {
    // Below the curve's start: unloaded elastically from its first point, down to the tension
    // the law allows.
    const double c0 = c.sound_speed(x.front());
    const double rho = x.front() + (std::max(p, -c.tensile_limit) - y.front()) / (c0 * c0);
    return {rho, x.front()};
  }
  // On the loading curve: the first rising segment that reaches p.
  for (std::size_t k = 0; k + 1 < x.size(); ++k)
    if (y[k + 1] > y[k] && p <= y[k + 1] && p >= y[k]) {
      const double rho = x[k] + (p - y[k]) * (x[k + 1] - x[k]) / (y[k + 1] - y[k]);
      return {rho, rho};
    }
  return {x.front(), x.front()}; // p == y.front() on a flat start
}

EosDensity invert(const materials::Hjc& m, double p, double) {
  // In tension the law is elastic down to -T.
  const double target = std::max(p, -m.T);
  const double rho =
      increasing_root([&](double r) { return materials::hjc_pressure(m, r, r, 0.0).p - target; },
                      m.rho0, std::numeric_limits<double>::infinity(), "HJC");
  return {rho, std::max(rho, m.rho0)};
}

/// Von Mises stress sqrt(3/2 s:s) of a deviator (Voigt, stress-like).
double von_mises(const double* s) {
  return std::sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                          2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
}

/// One particle's yield check: the distance from the surface's centre (q) and the surface (Y) in
/// von Mises measure, and the centre (the back stress for J2, else 0).
struct Check {
  double q = 0.0, Y = 0.0;
  bool applies = false;
};

Check check(const materials::NoStrength&, const ParticleFields&, int) {
  return {};
}
Check check(const materials::ElasticShear&, const ParticleFields&, int) {
  return {};
}
Check check(const materials::VonMises& law, const ParticleFields& F, int i) {
  const double* s = &F.S[6 * static_cast<std::size_t>(i)];
  const double* b = &F.back_stress[6 * static_cast<std::size_t>(i)];
  double xi[6];
  for (int c = 0; c < 6; ++c) xi[c] = s[c] - b[c];
  // |xi| vs sqrt(2/3) Y is q = sqrt(3/2) |xi| vs Y.
  return {von_mises(xi), materials::yield_stress(law.j2, F.alpha[i]), true};
}
template <class Law> Check check(const Law& law, const ParticleFields& F, int i) {
  return {von_mises(&F.S[6 * static_cast<std::size_t>(i)]),
          materials::current_yield(law, F.p[i], F.alpha[i], F.damage[i], 0.0), true};
}

/// Scales particle i's deviator about its centre (the back stress for J2) by `scale`.
void scale_deviator(ParticleFields& F, int i, double scale, bool about_back_stress) {
  double* s = &F.S[6 * static_cast<std::size_t>(i)];
  const double* b = &F.back_stress[6 * static_cast<std::size_t>(i)];
  for (int c = 0; c < 6; ++c) {
    const double centre = about_back_stress ? b[c] : 0.0;
    s[c] = centre + scale * (s[c] - centre);
  }
}

void check_sizes(int n, const std::vector<Vec6>& sigma, const std::vector<double>& plastic_strain,
                 const std::vector<Vec6>& back_stress) {
  const std::size_t count = static_cast<std::size_t>(n);
  MF_REQUIRE(sigma.size() == count, "SPH initial state: ", sigma.size(), " stresses for ", n,
             " particles");
  MF_REQUIRE(plastic_strain.empty() || plastic_strain.size() == count,
             "SPH initial state: ", plastic_strain.size(), " plastic strains for ", n,
             " particles");
  MF_REQUIRE(back_stress.empty() || back_stress.size() == count,
             "SPH initial state: ", back_stress.size(), " back stresses for ", n, " particles");
}

/// An ideal gas or a JWL explosive gives no density for a stress state.
void refuse_gases(const Hydro& h) {
  for (std::size_t m = 0; m < h.materials.size(); ++m) {
    const materials::EquationOfState& eos = h.materials[m].eos;
    if (h.groups.owned(m) > 0 && (std::holds_alternative<materials::IdealGas>(eos) ||
                                  std::holds_alternative<materials::JwlExplosive>(eos)))
      fail("SPH initial state: material '", h.materials[m].name, "' has an ",
           std::holds_alternative<materials::IdealGas>(eos) ? "ideal-gas" : "JWL",
           " equation of state, which gives no density for a stress state");
  }
}

/// Each owned particle's density from the pressure of its stress, its deviatoric stress (solids),
/// back stress and plastic strain, the rest of its history zeroed; returns the pressures.
std::vector<double> set_stress_and_density(Hydro& h, const std::vector<Vec6>& sigma,
                                           const std::vector<double>& plastic_strain,
                                           const std::vector<Vec6>& back_stress) {
  ParticleFields& F = h.fields;
  std::vector<double> pressure(static_cast<std::size_t>(h.particles.owned_count()));
  for (std::size_t m = 0; m < h.materials.size(); ++m) {
    const Material& mat = h.materials[m];
    const int* members = h.groups.of(m);
    const bool solid = mat.solid();
    std::visit(
        [&](const auto& eos) {
          for (int k = 0; k < h.groups.owned(m); ++k) {
            const int i = members[k];
            const std::size_t i6 = 6 * static_cast<std::size_t>(i);
            const Vec6& s = sigma[i];
            const double p = -(s(0) + s(1) + s(2)) / 3.0;
            pressure[i] = p;
            const EosDensity d = invert(eos, p, F.e[i]);
            F.rho[i] = d.rho;
            F.rho_max[i] = d.rho_max;
            for (int c = 0; c < 6; ++c) {
              F.S[i6 + c] = solid ? s(c) + (c < 3 ? p : 0.0) : 0.0;
              F.back_stress[i6 + c] = back_stress.empty() ? 0.0 : back_stress[i](c);
            }
            F.alpha[i] = plastic_strain.empty() ? 0.0 : plastic_strain[i];
            F.damage[i] = 0.0;
            F.strain_rate[i] = 0.0;
            F.failed[i] = 0;
          }
        },
        mat.eos);
  }
  return pressure;
}

/// Each particle's stress against its yield surface (a floor of 1e-12 of the stress scale on
/// the yield stress), returned to the surface from outside it when asked.
void check_yield(Hydro& h, double scale, bool return_to_surface, InitialStateReport& report) {
  ParticleFields& F = h.fields;
  const double floor = 1e-12 * scale;
  for (std::size_t m = 0; m < h.materials.size(); ++m) {
    const int* members = h.groups.of(m);
    std::visit(
        [&](const auto& law) {
          using Law = std::decay_t<decltype(law)>;
          for (int k = 0; k < h.groups.owned(m); ++k) {
            const int i = members[k];
            const Check c = check(law, F, i);
            if (!c.applies) continue;
            const double Y = std::max(c.Y, floor);
            const double ratio = c.q > 0.0 ? c.q / Y : 0.0;
            if (ratio > report.worst_ratio) report.worst_ratio = ratio, report.worst_particle = i;
            if (std::abs(c.q - c.Y) <= 1e-6 * Y) ++report.on_surface;
            if (c.q - c.Y > 1e-9 * Y) {
              ++report.over_surface;
              if (return_to_surface) {
                scale_deviator(F, i, c.Y / c.q, std::is_same_v<Law, materials::VonMises>);
                ++report.returned;
              }
            }
          }
        },
        h.materials[m].strength);
  }
}

} // namespace

EosDensity density_for_pressure(const materials::EquationOfState& eos, double p, double e) {
  return std::visit([&](const auto& law) { return invert(law, p, e); }, eos);
}

InitialStateReport set_initial_state(Hydro& h, const std::vector<Vec6>& sigma,
                                     const std::vector<double>& plastic_strain,
                                     const std::vector<Vec6>& back_stress, bool return_to_surface) {
  const int n = h.particles.owned_count();
  check_sizes(n, sigma, plastic_strain, back_stress);
  group_materials(h);
  refuse_gases(h);
  double scale = 0.0;
  for (const Vec6& s : sigma) scale = std::max(scale, s.cwiseAbs().maxCoeff());
  const std::vector<double> pressure =
      set_stress_and_density(h, sigma, plastic_strain, back_stress);
  refresh_ghosts(h);
  update_state(h);

  InitialStateReport report;
  for (int i = 0; i < n; ++i)
    report.density_mismatch =
        std::max(report.density_mismatch, std::abs(h.fields.p[i] - pressure[i]));
  if (scale > 0.0) report.density_mismatch /= scale;
  check_yield(h, scale, return_to_surface, report);
  commit_history(h);
  refresh_ghosts(h);
  update_state(h);
  return report;
}

void set_displacement(Hydro& h, const std::vector<double>& u) {
  particles::ParticleSet& P = h.particles;
  const std::size_t n3 = 3 * static_cast<std::size_t>(P.owned_count());
  MF_REQUIRE(u.size() == n3, "SPH displacement: ", u.size(), " values for ", n3 / 3,
             " particles (3 each)");
  std::copy(u.begin(), u.end(), P.u.begin());
  std::fill(P.v.begin(), P.v.begin() + static_cast<std::ptrdiff_t>(n3), 0.0);
  if (P.a.size() >= n3) std::fill(P.a.begin(), P.a.begin() + static_cast<std::ptrdiff_t>(n3), 0.0);
  refresh_ghosts(h);
}

} // namespace mf::sph
