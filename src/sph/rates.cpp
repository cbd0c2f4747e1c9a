#include "meshfree/sph/rates.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/sph/corrections.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/pair_kernel.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

namespace mf::sph {

namespace {
/// The dashpot force of particle k of a transmitting boundary at velocity v, plus its static
/// force when it holds one.
inline void boundary_force(const TransmittingBoundary& b, std::size_t k, const double* v,
                           double f[3]) {
  const double vn = v[0] * b.normal[0] + v[1] * b.normal[1] + v[2] * b.normal[2];
  for (int d = 0; d < 3; ++d) {
    const double normal_part = vn * b.normal[d];
    f[d] = -b.area[k] *
           (b.normal_impedance[k] * normal_part + b.shear_impedance[k] * (v[d] - normal_part));
  }
  if (!b.static_force.empty())
    for (int d = 0; d < 3; ++d) f[d] += b.static_force[3 * k + d];
}

/// The pairs of a row that interact now (r < 2 h_ij, r > 0), one array per quantity so that the
/// kernel loop runs on packed registers: partner, x_i - x_j, r^2, h_ij and grad_i W_ij / r_ij.
struct LivePairs {
  std::vector<int> j;
  std::vector<double> x0, x1, x2, r2, h, g;
  std::vector<double> vx, c, rho, visc; // v_ij . x_ij, c_j, rho_j, Monaghan's Pi_ij
  void reserve(std::size_t n) {
    if (j.size() >= n) return;
    for (std::vector<double>* v : {&x0, &x1, &x2, &r2, &h, &g, &vx, &c, &rho, &visc}) v->resize(n);
    j.resize(n);
  }
};

/// grad W / r for pairs [0, count) of `live` with the kernel's dimension fixed at compile time,
/// so that the loop has no branch the compiler cannot turn into a select.
template <int Dim> void kernel_slopes(kernels::SphKernel kernel, LivePairs& live, int count) {
  const double *r2 = live.r2.data(), *h = live.h.data();
  double* g = live.g.data();
  if (kernel == kernels::SphKernel::CubicSpline)
    for (int t = 0; t < count; ++t) {
      const double rr = std::sqrt(r2[t]);
      g[t] = kernels::cubic_spline_slope(Dim, rr, h[t]) / rr;
    }
  else
    for (int t = 0; t < count; ++t) {
      const double rr = std::sqrt(r2[t]);
      g[t] = kernels::wendland_c2_slope(Dim, rr, h[t]) / rr;
    }
}

/// The interacting pairs of row i, in the row's order; returns their count. The test and the
/// gradient are pair_gradient's, so every rate loop sums the same terms in the same order as one
/// walking the list with pair_gradient.
int live_pairs(const Hydro& s, const std::vector<double>& x, int i, LivePairs& live) {
  const long begin = s.pairs.offset[i], end = s.pairs.offset[i + 1];
  live.reserve(static_cast<std::size_t>(end - begin));
  const double* h = s.fields.h.data();
  const double xi[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
  int count = 0;
  // Without a branch: every pair is written at the next free slot, which advances only for an
  // interacting pair (about half of the list is the skin, in no predictable pattern).
  for (long k = begin; k < end; ++k) {
    const int j = s.pairs.partner[k];
    const double d0 = xi[0] - x[3 * j], d1 = xi[1] - x[3 * j + 1], d2 = xi[2] - x[3 * j + 2];
    double r2 = 0.0;
    r2 += d0 * d0;
    r2 += d1 * d1;
    r2 += d2 * d2;
    const double hij = 0.5 * (h[i] + h[j]);
    live.j[count] = j;
    live.x0[count] = d0, live.x1[count] = d1, live.x2[count] = d2;
    live.r2[count] = r2, live.h[count] = hij;
    count += !(r2 >= 4.0 * hij * hij) & (r2 != 0.0);
  }
  if (s.dim == 1)
    kernel_slopes<1>(s.settings.kernel, live, count);
  else if (s.dim == 2)
    kernel_slopes<2>(s.settings.kernel, live, count);
  else
    kernel_slopes<3>(s.settings.kernel, live, count);
  return count;
}

/// Monaghan's artificial viscosity Pi_ij of pairs [0, count) of particle i (Monaghan 1992, eq.
/// 4.2): mu = h_ij v_ij.x_ij / (r^2 + (phi h_ij)^2), Pi = (-alpha c_ij mu + beta mu^2) / rho_ij
/// for approaching pairs (v_ij.x_ij < 0), else 0. The partners' values are gathered first so that
/// the arithmetic, two divisions a pair, runs as one packed loop with a select for the sign test.
void viscosities(const Hydro& s, int i, LivePairs& live, int count) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const Settings& S = s.settings;
  for (int t = 0; t < count; ++t) {
    const int j = live.j[t];
    double vx = 0.0;
    vx += (P.v[3 * i] - P.v[3 * j]) * live.x0[t];
    vx += (P.v[3 * i + 1] - P.v[3 * j + 1]) * live.x1[t];
    vx += (P.v[3 * i + 2] - P.v[3 * j + 2]) * live.x2[t];
    live.vx[t] = vx;
    live.c[t] = F.c[j];
    live.rho[t] = F.rho[j];
  }
  const double ci = F.c[i], rhoi = F.rho[i], phi = S.phi, alpha = S.alpha, beta = S.beta;
  const double *vxs = live.vx.data(), *r2 = live.r2.data(), *h = live.h.data();
  const double *cj = live.c.data(), *rhoj = live.rho.data();
  double* visc = live.visc.data();
  for (int t = 0; t < count; ++t) {
    const double hij = h[t], vx = vxs[t];
    const double mu = hij * vx / (r2[t] + phi * phi * hij * hij);
    const double cij = 0.5 * (ci + cj[t]), rhoij = 0.5 * (rhoi + rhoj[t]);
    visc[t] = vx < 0.0 ? (-alpha * cij * mu + beta * mu * mu) / rhoij : 0.0;
  }
}

/// Velocity gradient L_i = sum_j (m_j / rho_j)(v_j - v_i) (x) grad_i W_ij of particle i over its
/// interacting pairs, and the Jaumann rate of its deviatoric stress with shear modulus G.
void jaumann_rate(const Hydro& s, Rates& r, int i, double G, const LivePairs& live, int count) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const double* C =
      s.settings.gradient_correction ? &r.correction[9 * static_cast<std::size_t>(i)] : nullptr;
  double L[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int t = 0; t < count; ++t) {
    const int j = live.j[t];
    const double xij[3] = {live.x0[t], live.x1[t], live.x2[t]};
    double gv[3];
    gradient_vector(C, live.g[t], xij, gv);
    const double vol = r.volume[j];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) L[a][b] += vol * (P.v[3 * j + a] - P.v[3 * i + a]) * gv[b];
  }
  double D[3][3], W[3][3], Si[3][3];
  const double* s6 = &F.S[6 * static_cast<std::size_t>(i)];
  const double Sm[3][3] = {{s6[0], s6[5], s6[4]}, {s6[5], s6[1], s6[3]}, {s6[4], s6[3], s6[2]}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      D[a][b] = 0.5 * (L[a][b] + L[b][a]);
      W[a][b] = 0.5 * (L[a][b] - L[b][a]);
      Si[a][b] = Sm[a][b];
    }
  const double trD = D[0][0] + D[1][1] + D[2][2];
  double dS[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double rot = 0.0;
      for (int c = 0; c < 3; ++c) rot += W[a][c] * Si[c][b] - Si[a][c] * W[c][b];
      dS[a][b] = 2.0 * G * (D[a][b] - (a == b ? trD / 3.0 : 0.0)) + rot;
    }
  double* out = &r.dS[6 * static_cast<std::size_t>(i)];
  out[0] = dS[0][0], out[1] = dS[1][1], out[2] = dS[2][2];
  out[3] = dS[1][2], out[4] = dS[0][2], out[5] = dS[0][1];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) r.grad_v[9 * static_cast<std::size_t>(i) + 3 * a + b] = L[a][b];
}
} // namespace

void compute_rates(const Hydro& s, Rates& r) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  if (s.groups.built_for != P.size())
    fail("SPH: the particles changed since they were grouped by material (update_state or "
         "refresh_neighbours groups them)");
  const Settings& S = s.settings;
  // Rates for the owned particles; ghosts (other ranks' particles, mirror images) only lend
  // their state.
  const int n = P.owned_count(), all = P.size(), dim = s.dim;
  r.x.resize(3 * static_cast<std::size_t>(all));
#pragma omp parallel for schedule(static)
  for (int k = 0; k < 3 * all; ++k) r.x[k] = P.X[k] + P.u[k];
  const bool corrected = S.gradient_correction;
  if (corrected) {
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
  // The per-particle factors of the pair terms, p / rho^2, 1 / rho^2 and m / rho: once per
  // particle here rather than once per pair (the same operations, so the same values).
  r.p_rho2.resize(all);
  r.inv_rho2.resize(all);
  r.volume.resize(all);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < all; ++i) {
    r.p_rho2[i] = F.p[i] / (F.rho[i] * F.rho[i]);
    r.inv_rho2[i] = 1.0 / (F.rho[i] * F.rho[i]);
    r.volume[i] = P.mass[i] / F.rho[i];
  }
  r.dv.assign(3 * static_cast<std::size_t>(all), 0.0);
  r.drho.assign(all, 0.0);
  r.de.assign(all, 0.0);
  const bool solids = s.any_solid();
  if (solids) {
    // Velocity gradient L_i = sum_j (m_j / rho_j)(v_j - v_i) (x) grad_i W_ij, and the Jaumann
    // rate of the deviatoric stress.
    r.grad_v.assign(9 * static_cast<std::size_t>(all), 0.0);
    r.dS.assign(6 * static_cast<std::size_t>(all), 0.0);
    // Each owned particle's shear modulus, the law dispatched once per material; -1: no
    // strength (no Jaumann rate).
    r.shear.assign(n, -1.0);
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
  // Gravity and damping (a += g - c v) on the owned particles that move.
  const bool body_force =
      s.gravity[0] != 0.0 || s.gravity[1] != 0.0 || s.gravity[2] != 0.0 || s.damping > 0.0;
  const double damping = std::max(s.damping, 0.0);
#pragma omp parallel
  {
    LivePairs live;
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < n; ++i) {
      const int count = live_pairs(s, r.x, i, live);
      if (solids && r.shear[i] >= 0.0) jaumann_rate(s, r, i, r.shear[i], live, count);
      viscosities(s, i, live, count);
      const double pi_rho2 = r.p_rho2[i];
      const double* si = &F.S[6 * static_cast<std::size_t>(i)];
      const double ri2 = r.inv_rho2[i];
      double acc[3] = {0.0, 0.0, 0.0}, drho = 0.0, de = 0.0;
      for (int t = 0; t < count; ++t) {
        const int j = live.j[t];
        const double xij[3] = {live.x0[t], live.x1[t], live.x2[t]};
        const double r2 = live.r2[t], g = live.g[t];
        const double vij[3] = {P.v[3 * i] - P.v[3 * j], P.v[3 * i + 1] - P.v[3 * j + 1],
                               P.v[3 * i + 2] - P.v[3 * j + 2]};
        const double hij = live.h[t];
        const double q = pi_rho2 + r.p_rho2[j] + live.visc[t];
        const double mj = P.mass[j];
        // The pair's gradient: with the correction, (C_i + C_j)/2 grad W, which stays
        // antisymmetric in i and j, so momentum is still conserved exactly.
        double gv[3];
        if (corrected) {
          double A[9];
          const double* ci = &r.correction[9 * static_cast<std::size_t>(i)];
          const double* cj = &r.correction[9 * static_cast<std::size_t>(j)];
          for (int c = 0; c < 9; ++c) A[c] = 0.5 * (ci[c] + cj[c]);
          gradient_vector(A, g, xij, gv);
        } else {
          gradient_vector(nullptr, g, xij, gv);
        }
        const double vg = vij[0] * gv[0] + vij[1] * gv[1] + vij[2] * gv[2];
        for (int d = 0; d < 3; ++d) acc[d] -= mj * q * gv[d];
        drho += mj * vg;
        de += 0.5 * mj * q * vg;
        if (solids) {
          // Deviatoric stress: dv_i += m_j (S_i/rho_i^2 + S_j/rho_j^2) . grad W and
          // de_i -= m_j / 2 (S_i/rho_i^2 + S_j/rho_j^2) : (v_ij (x) grad W).
          const double* sj = &F.S[6 * static_cast<std::size_t>(j)];
          const double rj2 = r.inv_rho2[j];
          double T[6];
          for (int c = 0; c < 6; ++c) T[c] = si[c] * ri2 + sj[c] * rj2;
          if (art) {
            // f^n (R_i + R_j), f = W(r) / W(dp) with dp the pair's mean initial spacing.
            const double dp = 0.5 * (r.spacing[i] + r.spacing[j]);
            const double f = kernels::sph_kernel(S.kernel, dim, std::sqrt(r2), hij) /
                             kernels::sph_kernel(S.kernel, dim, dp, hij);
            const double fn = std::pow(f, S.artificial_stress_exponent);
            const double* Ri = &r.art_stress[6 * static_cast<std::size_t>(i)];
            const double* Rj = &r.art_stress[6 * static_cast<std::size_t>(j)];
            for (int c = 0; c < 6; ++c) T[c] += fn * (Ri[c] + Rj[c]);
          }
          const double* gx = gv;
          const double Tg[3] = {T[0] * gx[0] + T[5] * gx[1] + T[4] * gx[2],
                                T[5] * gx[0] + T[1] * gx[1] + T[3] * gx[2],
                                T[4] * gx[0] + T[3] * gx[1] + T[2] * gx[2]};
          for (int d = 0; d < 3; ++d) acc[d] += mj * Tg[d];
          de -= 0.5 * mj * (vij[0] * Tg[0] + vij[1] * Tg[1] + vij[2] * Tg[2]);
        }
        if (S.penalty.pressure > 0.0 && P.material[i] != P.material[j]) {
          const double a = 0.5 * (r.spacing[i] + r.spacing[j]);
          const double r0 = S.penalty.distance * a, rr = std::sqrt(r2);
          if (rr < r0) {
            const double pe = r0 / rr;
            const double f = S.penalty.pressure * std::pow(a, dim - 1) *
                             (std::pow(pe, S.penalty.n1) - std::pow(pe, S.penalty.n2));
            for (int d = 0; d < 3; ++d) acc[d] += f / P.mass[i] * xij[d] / rr;
          }
        }
      }
      if (!F.fixed[i]) {
        if (body_force)
          for (int d = 0; d < 3; ++d) acc[d] += s.gravity[d] - damping * P.v[3 * i + d];
        for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = acc[d];
      }
      r.drho[i] = drho;
      r.de[i] = de;
    }
  }
  for (const SurfaceLoad& load : s.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      if (F.fixed[i]) continue;
      const double f = load.pulses[k](s.particles.time) * load.area[k] / P.mass[i];
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] += f * load.direction[d];
    }
  for (const SurfaceForce& held : s.forces)
    for (std::size_t k = 0; k < held.particles.size(); ++k) {
      const int i = held.particles[k];
      if (F.fixed[i]) continue;
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] += held.force[3 * k + d] / P.mass[i];
    }
  for (const TransmittingBoundary& b : s.transmitting)
    for (std::size_t k = 0; k < b.particles.size(); ++k) {
      const int i = b.particles[k];
      double f[3];
      boundary_force(b, k, &P.v[3 * static_cast<std::size_t>(i)], f);
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] += f[d] / P.mass[i];
    }
}

void external_forces(const Hydro& s, std::vector<int>& who, std::vector<double>& force) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  who.clear();
  force.clear();
  for (const SurfaceLoad& load : s.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      if (F.fixed[i]) continue;
      const double f = load.pulses[k](s.particles.time) * load.area[k];
      who.push_back(i);
      for (int d = 0; d < 3; ++d) force.push_back(f * load.direction[d]);
    }
  for (const SurfaceForce& held : s.forces)
    for (std::size_t k = 0; k < held.particles.size(); ++k) {
      const int i = held.particles[k];
      if (F.fixed[i]) continue;
      who.push_back(i);
      for (int d = 0; d < 3; ++d) force.push_back(held.force[3 * k + d]);
    }
  for (const TransmittingBoundary& b : s.transmitting)
    for (std::size_t k = 0; k < b.particles.size(); ++k) {
      double f[3];
      boundary_force(b, k, &P.v[3 * static_cast<std::size_t>(b.particles[k])], f);
      who.push_back(b.particles[k]);
      for (int d = 0; d < 3; ++d) force.push_back(f[d]);
    }
}
} // namespace mf::sph
