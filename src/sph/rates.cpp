#include "meshfree/sph/rates.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/corrections.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/pair_sums.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

namespace mf::sph {

namespace {
/// Current positions x = X + u of all particles, owned and ghosts.
void current_positions(const Hydro& s, Rates& r) {
  const particles::ParticleSet& P = s.particles;
  const int all = P.size();
  r.x.resize(3 * static_cast<std::size_t>(all));
#pragma omp parallel for schedule(static)
  for (int k = 0; k < 3 * all; ++k) r.x[k] = P.X[k] + P.u[k];
}

/// The kernel gradient correction matrices, the artificial stresses and the initial spacings
/// that the settings ask for, on the ghosts too.
void pair_corrections(const Hydro& s, Rates& r) {
  const particles::ParticleSet& P = s.particles;
  const Settings& S = s.settings;
  const int all = P.size(), dim = s.dim;
  if (S.gradient_correction) {
    correction_matrices(s, r.x, r.correction);
    exchange_remote(s, r.correction, 9);
    mirror_matrices(s, r.correction);
  }
  const bool art = S.artificial_stress > 0.0;
  if (art) {
    artificial_stresses(s, r.art_stress);
    exchange_remote(s, r.art_stress, 6);
    mirror_voigt(s, r.art_stress);
  }
  if (art || S.penalty.pressure > 0.0) {
    // Initial particle spacings (m / rho_ref)^(1/dim), once per call rather than per pair.
    r.spacing.resize(all);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < all; ++i) r.spacing[i] = std::pow(P.mass[i] / P.density[i], 1.0 / dim);
  }
}

/// What the pairs read of each particle, gathered here once per particle (the same operations
/// as per pair, so the same values).
void gather_records(const Hydro& s, bool solids, Rates& r) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const int all = P.size();
  r.xh.resize(4 * static_cast<std::size_t>(all));
  r.records.resize(Record::size * static_cast<std::size_t>(all));
#pragma omp parallel for schedule(static)
  for (int i = 0; i < all; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    for (int d = 0; d < 3; ++d) r.xh[4 * k + d] = r.x[3 * k + d];
    r.xh[4 * k + 3] = F.h[k];
    double* q = &r.records[Record::size * k];
    for (int d = 0; d < 3; ++d) q[Record::v + d] = P.v[3 * k + d];
    q[Record::mass] = P.mass[k];
    q[Record::volume] = P.mass[k] / F.rho[k];
    q[Record::p_rho2] = F.p[k] / (F.rho[k] * F.rho[k]);
    q[Record::c] = F.c[k];
    q[Record::rho] = F.rho[k];
    const double inv_rho2 = 1.0 / (F.rho[k] * F.rho[k]);
    for (int c = 0; c < 6; ++c) q[Record::T + c] = solids ? F.S[6 * k + c] * inv_rho2 : 0.0;
  }
}

/// Zeroed velocity gradients and stress rates, and each owned particle's shear modulus, the
/// law dispatched once per material; -1: no strength (no Jaumann rate).
void prepare_strength(const Hydro& s, Rates& r) {
  const ParticleFields& F = s.fields;
  const int all = s.particles.size();
  // Velocity gradient L_i = sum_j (m_j / rho_j)(v_j - v_i) (x) grad_i W_ij, and the Jaumann
  // rate of the deviatoric stress.
  r.grad_v.assign(9 * static_cast<std::size_t>(all), 0.0);
  r.dS.assign(6 * static_cast<std::size_t>(all), 0.0);
  r.shear.assign(s.particles.owned_count(), -1.0);
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const int* members = s.groups.of(m);
    const int count = s.groups.owned(m);
    std::visit(
        [&](const auto& law) {
          using Law = std::decay_t<decltype(law)>;
          if constexpr (!std::is_same_v<Law, materials::NoStrength>)
            for (int k = 0; k < count; ++k)
              r.shear[members[k]] = materials::shear_modulus(law, F.rho[members[k]]);
        },
        s.materials[m].strength);
  }
}

/// The accelerations of the boundary conditions; held components take whatever force it needs
/// to keep them at rest: the roller's reaction.
void add_boundary_accelerations(const Hydro& s, Rates& r) {
  for (std::size_t c = 0; c < s.conditions.size(); ++c)
    s.conditions[c].add_accelerations(s, s.particles.time, r.dv);
  const ParticleFields& F = s.fields;
  for (int i = 0; i < s.particles.owned_count(); ++i)
    if (F.held_axes[i])
      for (int d = 0; d < 3; ++d)
        if (F.held_axes[i] & (1 << d)) r.dv[3 * i + d] = 0.0;
}

} // namespace

void compute_rates(const Hydro& s, Rates& r) {
  if (s.groups.built_for != s.particles.size())
    fail("SPH: the particles changed since they were grouped by material (update_state or "
         "refresh_neighbours groups them)");
  // Rates for the owned particles; ghosts (other ranks' particles, mirror images) only lend
  // their state.
  const int all = s.particles.size();
  current_positions(s, r);
  pair_corrections(s, r);
  const bool solids = s.any_solid();
  gather_records(s, solids, r);
  r.dv.assign(3 * static_cast<std::size_t>(all), 0.0);
  r.drho.assign(all, 0.0);
  r.de.assign(all, 0.0);
  if (solids) prepare_strength(s, r);
  sum_pairs(s, r, solids);
  add_boundary_accelerations(s, r);
}

void external_forces(const Hydro& s, std::vector<int>& who, std::vector<double>& force) {
  who.clear();
  force.clear();
  for (std::size_t c = 0; c < s.conditions.size(); ++c)
    s.conditions[c].append_forces(s, s.particles.time, who, force);
}
} // namespace mf::sph
