#include "meshfree/sph/state.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/sph/detonation.hpp"
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

namespace mf::sph {

namespace {

/// Pressure and squared sound speed of particle i of a material with equation of state `eos`.
template <class Eos>
materials::PressureAndSound pressure_of(const Hydro& s, const Eos& eos, int i) {
  const ParticleFields& F = s.fields;
  return materials::pressure_and_sound(eos, F.rho[i], F.e[i], F.rho_max[i], F.damage[i]);
}

/// An explosive's pressure at its burn fraction; one with an unreacted equation of state is lit
/// here when the shock has compressed it by Settings::ignition_compression.
materials::PressureAndSound pressure_of(Hydro& s, const materials::JwlExplosive& x, int i) {
  ParticleFields& F = s.fields;
  if (x.unreacted && F.light_time[i] < 0.0 &&
      F.rho[i] >= (1.0 + s.settings.ignition_compression) * x.jwl.rho0)
    F.light_time[i] = s.particles.time;
  // A particle never lit is inert.
  const double f = F.light_time[i] >= 0.0 ? burn_fraction(x, s.particles.time, F.light_time[i],
                                                          F.h[i], F.rho[i], s.settings.burn_width)
                                          : 0.0;
  return materials::explosive_pressure(x, F.rho[i], F.e[i], f);
}

/// A solid's longitudinal sound speed adds 4G / (3 rho) to the bulk one; a fluid's adds nothing.
template <class Law> double shear_speed2(const Law& law, double rho) {
  return 4.0 * materials::shear_modulus(law, rho) / (3.0 * rho);
}
double shear_speed2(const materials::NoStrength&, double) {
  return 0.0;
}

/// Von Mises stress sqrt(3/2 S:S) of a deviator S (Voigt, stress-like).
double von_mises(const double* s) {
  return std::sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] +
                          2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
}

/// The elastic trial of a solid particle: S = S0 + dt dS with the plastic strain and damage of
/// the start of the step, and the equivalent deviatoric strain rate sqrt(2/3 D':D')
/// from the velocity gradient. A failed particle carries no deviatoric stress (returns false).
bool elastic_trial(ParticleFields& F, const StressHistory& start, const Rates& r, double dt,
                   int i) {
  const std::size_t i6 = 6 * static_cast<std::size_t>(i);
  double* si = &F.S[i6];
  if (F.failed[i]) {
    for (int c = 0; c < 6; ++c) si[c] = 0.0;
    return false;
  }
  for (int c = 0; c < 6; ++c) si[c] = start.S[i6 + c] + dt * r.dS[i6 + c];
  F.alpha[i] = start.alpha[i];
  F.damage[i] = start.damage[i];
  const double* L = &r.grad_v[9 * static_cast<std::size_t>(i)];
  const double tr = (L[0] + L[4] + L[8]) / 3.0;
  double dd = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double d = 0.5 * (L[3 * a + b] + L[3 * b + a]) - (a == b ? tr : 0.0);
      dd += d * d;
    }
  F.strain_rate[i] = std::sqrt(2.0 / 3.0 * dd);
  return true;
}

/// The return of each strength model, after the elastic trial of particle i.
void plastic_return(ParticleFields&, const materials::ElasticShear&, const StressHistory&,
                    const Rates&, double, int) {}

/// The Jaumann rate W b - b W of a symmetric tensor b (Voigt, stress-like) under the spin
/// W = (L - L^T) / 2 of the velocity gradient L (row-major), the rotation that the deviatoric
/// stress rate carries too.
materials::Vec6 jaumann_rotation(const double* L, const materials::Vec6& b) {
  const double B[3][3] = {{b(0), b(5), b(4)}, {b(5), b(1), b(3)}, {b(4), b(3), b(2)}};
  double W[3][3];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) W[a][c] = 0.5 * (L[3 * a + c] - L[3 * c + a]);
  const auto rot = [&](int a, int c) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += W[a][k] * B[k][c] - B[a][k] * W[k][c];
    return sum;
  };
  materials::Vec6 out;
  out << rot(0, 0), rot(1, 1), rot(2, 2), rot(1, 2), rot(0, 2), rot(0, 1);
  return out;
}

void plastic_return(ParticleFields& F, const materials::VonMises& law, const StressHistory& start,
                    const Rates& r, double dt, int i) {
  // The J2 return of the Galerkin solver on the integrated trial deviator (materials/
  // j2_plasticity), with the particle's back stress. With kinematic hardening the back stress
  // turns with the material like S: b = b0 + dt (W b - b W), b at the rates' state.
  const std::size_t i6 = 6 * static_cast<std::size_t>(i);
  double* si = &F.S[i6];
  const materials::Vec6 trial = Eigen::Map<const materials::Vec6>(si);
  materials::Vec6 beta = Eigen::Map<const materials::Vec6>(&start.back_stress[i6]);
  if (law.j2.H_kinematic > 0.0)
    beta += dt * jaumann_rotation(&r.grad_v[9 * static_cast<std::size_t>(i)],
                                  Eigen::Map<const materials::Vec6>(&F.back_stress[i6]));
  const materials::J2Return ret = materials::j2_radial_return(law.j2, trial, beta, start.alpha[i]);
  if (ret.plastic) {
    for (int c = 0; c < 6; ++c) si[c] = ret.deviator(c);
    F.alpha[i] = ret.alpha;
    beta = ret.back_stress;
  }
  for (int c = 0; c < 6; ++c) F.back_stress[i6 + c] = beta(c);
}

/// Perfectly plastic at the current pressure (and damage): radial return to Y, the hardening
/// variable growing by the model's alpha_increment ((q - Y) / 3G for von Mises-type surfaces);
/// HJC adds its damage.
template <class Law>
void plastic_return(ParticleFields& F, const Law& law, const StressHistory& start, const Rates&,
                    double, int i) {
  double* si = &F.S[6 * static_cast<std::size_t>(i)];
  const double q = von_mises(si);
  const double Y =
      materials::current_yield(law, F.p[i], start.alpha[i], start.damage[i], F.strain_rate[i]);
  const materials::YieldReturn ret =
      materials::perfectly_plastic_return(q, Y, materials::shear_modulus(law, F.rho[i]));
  if (ret.plastic)
    for (int c = 0; c < 6; ++c) si[c] *= ret.scale;
  F.alpha[i] = start.alpha[i] + materials::alpha_increment(law, ret);
  if constexpr (std::is_same_v<Law, materials::Hjc>)
    F.damage[i] =
        std::min(1.0, start.damage[i] + materials::hjc_damage_increment(law, F.rho[i], F.rho_max[i],
                                                                        F.p[i], ret.dalpha));
}

} // namespace

void update_state(Hydro& s) {
  group_materials(s);
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  const double inv_dim = 1.0 / s.dim;
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const int* members = s.groups.of(m);
    const int count = s.groups.count(m);
    std::visit(
        [&](const auto& eos, const auto& strength) {
#pragma omp parallel for schedule(static)
          for (int k = 0; k < count; ++k) {
            const int i = members[k];
            F.h[i] = F.h_ref[i] * std::pow(P.density[i] / F.rho[i], inv_dim);
            const materials::PressureAndSound ps = pressure_of(s, eos, i);
            F.p[i] = F.failed[i] ? std::max(ps.p, 0.0) : ps.p;
            F.c[i] = std::sqrt(std::max(ps.c2, 0.0) + shear_speed2(strength, F.rho[i]));
          }
        },
        s.materials[m].eos, s.materials[m].strength);
  }
}

StressHistory stress_history(const Hydro& s) {
  const ParticleFields& F = s.fields;
  return {F.S, F.back_stress, F.alpha, F.damage};
}

void update_stress(Hydro& s, const StressHistory& start, const Rates& r, double dt) {
  ParticleFields& F = s.fields;
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const int* members = s.groups.of(m);
    const int count = s.groups.owned(m);
    std::visit(
        [&](const auto& law) {
          using Law = std::decay_t<decltype(law)>;
          if constexpr (!std::is_same_v<Law, materials::NoStrength>) {
#pragma omp parallel for schedule(static)
            for (int k = 0; k < count; ++k) {
              const int i = members[k];
              if (elastic_trial(F, start, r, dt, i)) plastic_return(F, law, start, r, dt, i);
            }
          }
        },
        s.materials[m].strength);
  }
}

void commit_history(Hydro& s) {
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  const int n = P.size();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) F.rho_max[i] = std::max(F.rho_max[i], F.rho[i]);
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const Material& mat = s.materials[m];
    if (!mat.solid()) continue;
    const bool by_damage = std::holds_alternative<materials::Hjc>(mat.strength);
    const int* members = s.groups.of(m);
    const int count = s.groups.count(m);
#pragma omp parallel for schedule(static)
    for (int k = 0; k < count; ++k) {
      const int i = members[k];
      if (F.failed[i]) continue;
      if ((by_damage && F.damage[i] >= 1.0) ||
          (mat.failure_strain > 0.0 && F.alpha[i] >= mat.failure_strain)) {
        F.failed[i] = 1;
        for (int c = 0; c < 6; ++c) F.S[6 * static_cast<std::size_t>(i) + c] = 0.0;
      }
    }
  }
}

} // namespace mf::sph
