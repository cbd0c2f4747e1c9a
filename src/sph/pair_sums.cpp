#include "meshfree/sph/pair_sums.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/sph/live_pairs.hpp"
#include <algorithm>
#include <cmath>
#include <omp.h>
#include <vector>
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define MF_SPH_AVX2 1
#else
#define MF_SPH_AVX2 0
#endif

// Every step of a row is inlined into the row ranges below, which are compiled once for the
// baseline and once for AVX2 (the same source, so four lanes where the baseline packs two; no
// contraction and no reassociation, so the same numbers bit for bit).
#define MF_ROW_STEP __attribute__((always_inline)) inline

namespace mf::sph {

namespace {

/// The values of a row's own particle i that every pair of the row reads, gathered once per row.
struct RowParticle {
  int i;
  double v[3], p_rho2, mass, volume, spacing, c, rho;
  double T[6];     // S_i / rho_i^2 (solids)
  const double* C; // the correction matrix, or null
  const double* R; // the artificial stress, or null
  int material;
};

template <bool Solids> MF_ROW_STEP RowParticle row_particle(const Hydro& s, const Rates& r, int i) {
  const std::size_t k = static_cast<std::size_t>(i);
  const double* q = &r.records[Record::size * k];
  RowParticle o;
  o.i = i;
  for (int d = 0; d < 3; ++d) o.v[d] = q[Record::v + d];
  o.p_rho2 = q[Record::p_rho2];
  o.mass = q[Record::mass];
  o.volume = q[Record::volume];
  const bool spaced = s.settings.artificial_stress > 0.0 || s.settings.penalty.pressure > 0.0;
  o.spacing = spaced ? r.spacing[k] : 0.0;
  o.c = q[Record::c];
  o.rho = q[Record::rho];
  if constexpr (Solids)
    for (int c = 0; c < 6; ++c) o.T[c] = q[Record::T + c];
  o.C = s.settings.gradient_correction ? &r.correction[9 * k] : nullptr;
  o.R = s.settings.artificial_stress > 0.0 ? &r.art_stress[6 * k] : nullptr;
  o.material = s.particles.material[k];
  return o;
}

/// The stress components (Voigt xx yy zz yz xz xy) that act in Dim dimensions: the in-plane or
/// in-line ones (the others multiply zero gradient components).
template <int Dim> constexpr bool stress_component_acts(int c) {
  return Dim == 3 || c == 0 || (Dim == 2 && (c == 1 || c == 5));
}

/// The partners' values of pairs [0, count), gathered into the row's arrays: v_ij, m_j, V_j,
/// c_j, rho_j, p_j / rho_j^2 and, for solids, T = S_i / rho_i^2 + S_j / rho_j^2.
template <int Dim, bool Solids>
MF_ROW_STEP void gather_partners(const Rates& r, const RowParticle& o, LivePairs& live, int count) {
  for (int t = 0; t < count; ++t) {
    const double* q = &r.records[Record::size * static_cast<std::size_t>(live.j[t])];
    for (int d = 0; d < Dim; ++d) live.v[d][t] = o.v[d] - q[Record::v + d];
    live.m[t] = q[Record::mass];
    live.vol[t] = q[Record::volume];
    live.q[t] = q[Record::p_rho2];
    live.c[t] = q[Record::c];
    live.rho[t] = q[Record::rho];
    if constexpr (Solids)
      for (int c = 0; c < 6; ++c)
        if (stress_component_acts<Dim>(c)) live.T[c][t] = o.T[c] + q[Record::T + c];
  }
}

/// Monaghan's artificial viscosity Pi_ij (Monaghan 1992, eq. 4.2) added to q:
/// mu = h_ij v_ij.x_ij / D with D = r^2 + (phi h_ij)^2, Pi = (-alpha c_ij mu + beta mu^2) / rho_ij
/// for approaching pairs (v_ij.x_ij < 0), else 0; q = p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij.
/// Pi is evaluated as h v.x (beta h v.x - alpha c_ij D) / (D^2 rho_ij), one division a pair.
template <int Dim>
MF_ROW_STEP void viscosities(const Settings& S, const RowParticle& o, LivePairs& live, int count) {
  const double phi2 = S.phi * S.phi, alpha = S.alpha, beta = S.beta;
#pragma GCC ivdep
  for (int t = 0; t < count; ++t) {
    double vx = live.v[0][t] * live.x[0][t];
    if constexpr (Dim > 1) vx += live.v[1][t] * live.x[1][t];
    if constexpr (Dim > 2) vx += live.v[2][t] * live.x[2][t];
    const double hij = live.h[t], hvx = hij * vx;
    const double D = live.r2[t] + phi2 * hij * hij;
    const double cij = 0.5 * (o.c + live.c[t]), rhoij = 0.5 * (o.rho + live.rho[t]);
    const double visc = vx < 0.0 ? hvx * (beta * hvx - alpha * cij * D) / (D * D * rhoij) : 0.0;
    live.q[t] = o.p_rho2 + live.q[t] + visc;
  }
}

/// The pair's kernel gradient over the model's Dim axes: g x_ij, or g A x_ij for the 3x3 correction
/// A (row-major); components beyond Dim are zero, as are the terms left out.
template <int Dim>
MF_ROW_STEP void gradient_along(const double* A, double g, const double xij[3], double out[3]) {
  for (int a = 0; a < 3; ++a) {
    if (a >= Dim) {
      out[a] = 0.0;
    } else if (!A) {
      out[a] = g * xij[a];
    } else {
      double Ax = A[3 * a] * xij[0];
      for (int b = 1; b < Dim; ++b) Ax += A[3 * a + b] * xij[b];
      out[a] = g * Ax;
    }
  }
}

/// The kernel gradients of pairs [0, count): g x_ij or, with the correction, the pair's
/// (C_i + C_j)/2 g x_ij, which stays antisymmetric in i and j so that momentum is still conserved
/// exactly, and each end's own C g x_ij for the velocity gradient.
template <int Dim>
MF_ROW_STEP void kernel_gradients(const Rates& r, const RowParticle& o, LivePairs& live,
                                  int count) {
  if (!o.C) {
#pragma GCC ivdep
    for (int t = 0; t < count; ++t)
      for (int d = 0; d < Dim; ++d) live.gv[d][t] = live.g[t] * live.x[d][t];
    return;
  }
  for (int t = 0; t < count; ++t) {
    const double* Cj = &r.correction[9 * static_cast<std::size_t>(live.j[t])];
    double A[9], xij[3] = {live.x[0][t], 0.0, 0.0}, gv[3], gi[3], gj[3];
    for (int d = 1; d < Dim; ++d) xij[d] = live.x[d][t];
    for (int c = 0; c < 9; ++c) A[c] = 0.5 * (o.C[c] + Cj[c]);
    gradient_along<Dim>(A, live.g[t], xij, gv);
    gradient_along<Dim>(o.C, live.g[t], xij, gi);
    gradient_along<Dim>(Cj, live.g[t], xij, gj);
    for (int d = 0; d < Dim; ++d)
      live.gv[d][t] = gv[d], live.gi[d][t] = gi[d], live.gj[d][t] = gj[d];
  }
}

/// Gray, Monaghan & Swift's (2001) artificial stress added to T: f^n (R_i + R_j) with
/// f = W(r) / W(dp), dp the pair's mean initial spacing.
template <int Dim>
MF_ROW_STEP void artificial_stress(const Hydro& s, const Rates& r, const RowParticle& o,
                                   LivePairs& live, int count) {
  const Settings& S = s.settings;
  for (int t = 0; t < count; ++t) {
    const std::size_t j = static_cast<std::size_t>(live.j[t]);
    const double dp = 0.5 * (o.spacing + r.spacing[j]), inv_h = 1.0 / live.h[t];
    const double f = kernels::sph_kernel_profile(S.kernel, s.dim, std::sqrt(live.r2[t]) * inv_h) /
                     kernels::sph_kernel_profile(S.kernel, s.dim, dp * inv_h);
    double fn = f; // f^n by products: std::pow took 35% of a run with artificial stress
    for (int k = 1; k < S.artificial_stress_exponent; ++k) fn *= f;
    const double* Rj = &r.art_stress[6 * j];
    for (int c = 0; c < 6; ++c)
      if (stress_component_acts<Dim>(c)) live.T[c][t] += fn * (o.R[c] + Rj[c]);
  }
}

/// The terms of pairs [0, count) that both ends share ([Altafi 2018] eqs. 3-41, 3-48 and 3-64):
/// the momentum term f = q gv - T gv (dv_i = -m_j f, dv_j = +m_i f), v_ij . gv (drho_i = m_j v.gv)
/// and w = q v_ij . gv - v_ij . T gv (de_i = m_j w / 2). Each is symmetric in i and j or changes
/// sign with x_ij, so one evaluation serves both ends. Components beyond Dim are zero: the
/// motion and the shear stresses out of the model's plane or line are.
template <int Dim, bool Solids> MF_ROW_STEP void pair_terms(LivePairs& live, int count) {
  constexpr int voigt[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
#pragma GCC ivdep
  for (int t = 0; t < count; ++t) {
    double vg = live.v[0][t] * live.gv[0][t];
    for (int d = 1; d < Dim; ++d) vg += live.v[d][t] * live.gv[d][t];
    const double q = live.q[t];
    live.vg[t] = vg;
    if constexpr (Solids) {
      double Tg[3], vTg = 0.0;
      for (int a = 0; a < Dim; ++a) {
        double sum = live.T[voigt[a][0]][t] * live.gv[0][t];
        for (int b = 1; b < Dim; ++b) sum += live.T[voigt[a][b]][t] * live.gv[b][t];
        Tg[a] = sum;
        vTg += live.v[a][t] * sum;
      }
      for (int d = 0; d < Dim; ++d) live.f[d][t] = q * live.gv[d][t] - Tg[d];
      live.w[t] = q * vg - vTg;
    } else {
      for (int d = 0; d < Dim; ++d) live.f[d][t] = q * live.gv[d][t];
      live.w[t] = q * vg;
    }
  }
}

/// The inter-material penalty of pairs [0, count) (Settings::Penalty): a repulsion
/// P a^(dim-1) ((r0/r)^n1 - (r0/r)^n2) along x_ij for r < r0 = distance * a between particles
/// of different materials, a the pair's mean spacing; push = that force / r, or 0.
MF_ROW_STEP void penalties(const Hydro& s, const Rates& r, const RowParticle& o, LivePairs& live,
                           int count) {
  const Settings::Penalty& pen = s.settings.penalty;
  for (int t = 0; t < count; ++t) {
    const std::size_t j = static_cast<std::size_t>(live.j[t]);
    live.push[t] = 0.0;
    if (o.material == s.particles.material[j]) continue;
    const double a = 0.5 * (o.spacing + r.spacing[j]);
    const double r0 = pen.distance * a, rr = std::sqrt(live.r2[t]);
    if (rr >= r0) continue;
    const double pe = r0 / rr;
    live.push[t] =
        pen.pressure * std::pow(a, s.dim - 1) * (std::pow(pe, pen.n1) - std::pow(pe, pen.n2)) / rr;
  }
}

/// Row i's interacting pairs and all their terms, pass by pass.
template <int Dim, bool Solids>
MF_ROW_STEP int row_terms(const Hydro& s, const Rates& r, const neighbors::PairList& list,
                          const RowParticle& o, LivePairs& live, SimdTarget target) {
  const int count = select_live_pairs(Dim, list, r.xh.data(), o.i, s.settings.kernel, live, target);
  gather_partners<Dim, Solids>(r, o, live, count);
  viscosities<Dim>(s.settings, o, live, count);
  kernel_gradients<Dim>(r, o, live, count);
  if (Solids && o.R) artificial_stress<Dim>(s, r, o, live, count);
  pair_terms<Dim, Solids>(live, count);
  if (s.settings.penalty.pressure > 0.0) penalties(s, r, o, live, count);
  return count;
}

/// Row i's own sums over its pairs: dv_i = -sum m_j f (+ the penalty / m_i), drho_i, de_i and,
/// for solids, L_i = -sum V_j v_ij (x) C_i g x_ij. Even and odd pairs are summed apart (two
/// chains of additions instead of one, in packed registers) and the two sums added at the end,
/// an order fixed by the row alone.
template <int Dim, bool Solids>
MF_ROW_STEP void row_sums(const Settings& S, const RowParticle& o, const LivePairs& live, int count,
                          double a[3], double& drho, double& de, double L[9]) {
  constexpr int width = 2 + Dim + (Solids ? Dim * Dim : 0);
  double sum[2][width] = {};
  const std::vector<double>* gi = o.C ? live.gi : live.gv;
  const bool penalty = S.penalty.pressure > 0.0;
  const auto add = [&](int t, double* u) {
    const double mj = live.m[t];
    for (int d = 0; d < Dim; ++d) u[d] -= mj * live.f[d][t];
    u[Dim] += mj * live.vg[t];
    u[Dim + 1] += 0.5 * mj * live.w[t];
    if (penalty)
      for (int d = 0; d < Dim; ++d) u[d] += live.push[t] / o.mass * live.x[d][t];
    if constexpr (Solids)
      for (int p = 0; p < Dim; ++p)
        for (int q = 0; q < Dim; ++q)
          u[Dim + 2 + Dim * p + q] -= live.vol[t] * live.v[p][t] * gi[q][t];
  };
  int t = 0;
  for (; t + 1 < count; t += 2) add(t, sum[0]), add(t + 1, sum[1]);
  if (t < count) add(t, sum[0]);
  for (int d = 0; d < Dim; ++d) a[d] += sum[0][d] + sum[1][d];
  drho += sum[0][Dim] + sum[1][Dim];
  de += sum[0][Dim + 1] + sum[1][Dim + 1];
  if constexpr (Solids)
    for (int p = 0; p < Dim; ++p)
      for (int q = 0; q < Dim; ++q)
        L[3 * p + q] += sum[0][Dim + 2 + Dim * p + q] + sum[1][Dim + 2 + Dim * p + q];
}

/// The Jaumann rate of a deviatoric stress S (Voigt: xx yy zz yz xz xy) under the velocity
/// gradient L with shear modulus G: dS = 2 G dev D + W S - S W, D and W the symmetric and
/// antisymmetric parts of L. L is zero beyond the model's Dim axes and so are the shear stresses
/// out of its plane or line, so the rotation terms over the other axes (exact zeros) are left out.
template <int Dim>
MF_ROW_STEP void jaumann_rate(const double L[9], const double s6[6], double G, double out[6]) {
  double D[3][3], W[3][3];
  const double Sm[3][3] = {{s6[0], s6[5], s6[4]}, {s6[5], s6[1], s6[3]}, {s6[4], s6[3], s6[2]}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      D[a][b] = 0.5 * (L[3 * a + b] + L[3 * b + a]);
      W[a][b] = 0.5 * (L[3 * a + b] - L[3 * b + a]);
    }
  const double trD = D[0][0] + D[1][1] + D[2][2];
  double dS[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      double rot = 0.0;
      if (a < Dim && b < Dim)
        for (int c = 0; c < Dim; ++c) rot += W[a][c] * Sm[c][b] - Sm[a][c] * W[c][b];
      dS[a][b] = 2.0 * G * (D[a][b] - (a == b ? trD / 3.0 : 0.0)) + rot;
    }
  out[0] = dS[0][0], out[1] = dS[1][1], out[2] = dS[2][2];
  out[3] = dS[1][2], out[4] = dS[0][2], out[5] = dS[0][1];
}

/// Adds gravity and damping (a += g - c v) to an owned particle's acceleration and stores it,
/// or 0 for a fixed particle.
MF_ROW_STEP void store_acceleration(const Hydro& s, Rates& r, int i, double acc[3]) {
  if (s.fields.fixed[i]) {
    for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = 0.0;
    return;
  }
  const double* v = &s.particles.v[3 * static_cast<std::size_t>(i)];
  if (s.body.any()) {
    const double damping = std::max(s.body.damping, 0.0);
    for (int d = 0; d < 3; ++d) acc[d] += s.body.gravity[d] - damping * v[d];
  }
  for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = acc[d];
}

/// The velocity gradient and Jaumann rate of owned particle i from its summed L; particles
/// without strength keep zeros.
template <int Dim>
MF_ROW_STEP void store_stress_rate(const Hydro& s, Rates& r, int i, const double L[9]) {
  double* grad = &r.grad_v[9 * static_cast<std::size_t>(i)];
  double* dS = &r.dS[6 * static_cast<std::size_t>(i)];
  if (r.shear[i] < 0.0) {
    for (int c = 0; c < 9; ++c) grad[c] = 0.0;
    for (int c = 0; c < 6; ++c) dS[c] = 0.0;
    return;
  }
  for (int c = 0; c < 9; ++c) grad[c] = L[c];
  jaumann_rate<Dim>(L, &s.fields.S[6 * static_cast<std::size_t>(i)], r.shear[i], dS);
}

/// The partners' side of row i's pairs (x_ji = -x_ij, v_ji = -v_ij: f changes sign, v.gv and w do
/// not), added at j - base of the thread's outputs; ghosts (j >= n) are left to their owners.
template <int Dim, bool Solids>
MF_ROW_STEP void partner_sums(const Settings& S, const RowParticle& o, const LivePairs& live,
                              int count, int n, int base, double* acc, double* drho, double* de,
                              double* L) {
  const double mi = o.mass, vol_i = o.volume;
  const std::vector<double>* gj = o.C ? live.gj : live.gv;
  for (int t = 0; t < count; ++t) {
    const int j = live.j[t];
    if (j >= n) continue;
    const std::size_t k = static_cast<std::size_t>(j - base);
    for (int d = 0; d < Dim; ++d) acc[3 * k + d] += mi * live.f[d][t];
    drho[k] += mi * live.vg[t];
    de[k] += 0.5 * mi * live.w[t];
    if (S.penalty.pressure > 0.0)
      for (int d = 0; d < Dim; ++d) acc[3 * k + d] -= live.push[t] / live.m[t] * live.x[d][t];
    if constexpr (Solids)
      for (int p = 0; p < Dim; ++p)
        for (int q = 0; q < Dim; ++q) L[9 * k + 3 * p + q] -= vol_i * live.v[p][t] * gj[q][t];
  }
}

/// A row's own particle, its interacting pairs with their terms, and its own sums over them.
struct Row {
  RowParticle o;
  int count = 0;
  double a[3] = {0.0, 0.0, 0.0}, drho = 0.0, de = 0.0;
  double L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};

template <int Dim, bool Solids>
MF_ROW_STEP Row row_of(const Hydro& s, const Rates& r, const neighbors::PairList& list, int i,
                       LivePairs& live, SimdTarget target) {
  Row w;
  w.o = row_particle<Solids>(s, r, i);
  w.count = row_terms<Dim, Solids>(s, r, list, w.o, live, target);
  row_sums<Dim, Solids>(s.settings, w.o, live, w.count, w.a, w.drho, w.de, w.L);
  return w;
}

/// Rows [lo, hi) of the whole list, each summed into its own outputs.
template <int Dim, bool Solids>
MF_ROW_STEP void whole_rows_body(const Hydro& s, Rates& r, int lo, int hi, LivePairs& live,
                                 SimdTarget target) {
  for (int i = lo; i < hi; ++i) {
    Row w = row_of<Dim, Solids>(s, r, s.neighbours.pairs, i, live, target);
    store_acceleration(s, r, i, w.a);
    r.drho[i] = w.drho;
    r.de[i] = w.de;
    if constexpr (Solids) store_stress_rate<Dim>(s, r, i, w.L);
  }
}

/// Where a thread's half rows put their sums: r's own arrays (base 0) or the thread's buffer
/// over [base, owned).
struct HalfOutputs {
  double *acc, *drho, *de, *L;
  int base;
};

/// Rows [lo, hi) of the half list: each row's own sums, and its partners' side into `out`.
template <int Dim, bool Solids>
MF_ROW_STEP void half_rows_body(const Hydro& s, const Rates& r, int lo, int hi, LivePairs& live,
                                const HalfOutputs& out, SimdTarget target) {
  const int n = s.particles.owned_count();
  for (int i = lo; i < hi; ++i) {
    const Row w = row_of<Dim, Solids>(s, r, s.neighbours.half_pairs, i, live, target);
    partner_sums<Dim, Solids>(s.settings, w.o, live, w.count, n, out.base, out.acc, out.drho,
                              out.de, out.L);
    const std::size_t ib = static_cast<std::size_t>(i - out.base);
    for (int d = 0; d < 3; ++d) out.acc[3 * ib + d] += w.a[d];
    out.drho[ib] += w.drho;
    out.de[ib] += w.de;
    if constexpr (Solids)
      for (int c = 0; c < 9; ++c) out.L[9 * ib + c] += w.L[c];
  }
}

/// The row ranges on a target: compiled for the baseline, and for AVX2 where the compiler and
/// the processor have it (SimdTarget::Avx512 takes these too). The AVX2 ones clear the vector
/// registers' upper halves before the baseline code runs again (left dirty, every later SSE
/// instruction of the process waits on them).
template <int Dim, bool Solids> struct RowRanges {
#if MF_SPH_AVX2
  __attribute__((target("avx2"))) static void whole_avx2(const Hydro& s, Rates& r, int lo, int hi,
                                                         LivePairs& live) {
    whole_rows_body<Dim, Solids>(s, r, lo, hi, live, SimdTarget::Avx2);
    _mm256_zeroupper();
  }
  __attribute__((target("avx2"))) static void half_avx2(const Hydro& s, const Rates& r, int lo,
                                                        int hi, LivePairs& live,
                                                        const HalfOutputs& out) {
    half_rows_body<Dim, Solids>(s, r, lo, hi, live, out, SimdTarget::Avx2);
    _mm256_zeroupper();
  }
#endif
  static void whole(SimdTarget t, const Hydro& s, Rates& r, int lo, int hi, LivePairs& live) {
#if MF_SPH_AVX2
    if (t != SimdTarget::Baseline) return whole_avx2(s, r, lo, hi, live);
#endif
    whole_rows_body<Dim, Solids>(s, r, lo, hi, live, SimdTarget::Baseline);
  }
  static void half(SimdTarget t, const Hydro& s, const Rates& r, int lo, int hi, LivePairs& live,
                   const HalfOutputs& out) {
#if MF_SPH_AVX2
    if (t != SimdTarget::Baseline) return half_avx2(s, r, lo, hi, live, out);
#endif
    half_rows_body<Dim, Solids>(s, r, lo, hi, live, out, SimdTarget::Baseline);
  }
};

/// Deterministic sums (settings.deterministic): every owned particle sums its whole row in the
/// row's order (increasing global id, mirror images after), so its rates do not depend on the
/// threads or the ranks; each pair is evaluated from both ends. Rows are dealt out 64 at a time.
template <int Dim, bool Solids> void full_rows(const Hydro& s, Rates& r, SimdTarget target) {
  const int n = s.particles.owned_count();
  const int chunks = (n + 63) / 64;
#pragma omp parallel
  {
    LivePairs live;
#pragma omp for schedule(dynamic, 1)
    for (int c = 0; c < chunks; ++c)
      RowRanges<Dim, Solids>::whole(target, s, r, 64 * c, std::min(n, 64 * c + 64), live);
  }
}

/// Each pair once, Newton's third law (the default): the half list holds partner j > i only, and
/// the pair's terms go to both ends. Thread t takes rows [first_row[t], first_row[t + 1]) with an
/// equal share of the pairs; its reactions on partners land in its own buffer over
/// [first_row[t], owned) (thread 0 writes the outputs directly), and the buffers are added in
/// thread order afterwards. A pair with a ghost (another rank's particle, a mirror image) gives
/// its terms to the owned particle only; the ghost's owner sums its own side. The sums run in an
/// order that depends on the threads and ranks.
template <int Dim, bool Solids> void half_rows(const Hydro& s, Rates& r, SimdTarget target) {
  const int n = s.particles.owned_count();
  const neighbors::PairList& half = s.neighbours.half_pairs;
  const long total = half.offset[n];
  // Per particle: acceleration (3), drho, de and with strength L (9).
  constexpr int stride = Solids ? 14 : 5;
  std::vector<int> first_row;
  std::vector<double*> buffers;
#pragma omp parallel
  {
    const int T = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
    {
      first_row.assign(T + 1, n);
      for (int q = 0; q < T; ++q)
        first_row[q] = static_cast<int>(
            std::lower_bound(half.offset.begin(), half.offset.begin() + n, total * q / T) -
            half.offset.begin());
      first_row[0] = 0;
      buffers.assign(T, nullptr);
    }
    const int lo = first_row[t], hi = first_row[t + 1];
    // Thread 0 sums into r.dv / drho / de / grad_v; thread t > 0 into `own` over [lo, n).
    thread_local std::vector<double> own;
    double *acc = r.dv.data(), *drho = r.drho.data(), *de = r.de.data();
    double* L = Solids ? r.grad_v.data() : nullptr;
    int base = 0;
    if (t > 0) {
      const std::size_t len = static_cast<std::size_t>(n - lo);
      own.assign(stride * len, 0.0);
      acc = own.data(), drho = acc + 3 * len, de = drho + len;
      L = Solids ? de + len : nullptr;
      base = lo;
      buffers[t] = own.data();
    }
    LivePairs live;
    RowRanges<Dim, Solids>::half(target, s, r, lo, hi, live, {acc, drho, de, L, base});
#pragma omp barrier
#pragma omp for schedule(static)
    for (int i = 0; i < n; ++i) {
      for (int q = 1; q < T; ++q) {
        if (i < first_row[q]) continue;
        const std::size_t len = static_cast<std::size_t>(n - first_row[q]);
        const std::size_t k = static_cast<std::size_t>(i - first_row[q]);
        const double* b = buffers[q];
        for (int d = 0; d < 3; ++d) r.dv[3 * i + d] += b[3 * k + d];
        r.drho[i] += b[3 * len + k];
        r.de[i] += b[4 * len + k];
        if constexpr (Solids)
          for (int c = 0; c < 9; ++c) r.grad_v[9 * i + c] += b[5 * len + 9 * k + c];
      }
      double a[3] = {r.dv[3 * i], r.dv[3 * i + 1], r.dv[3 * i + 2]};
      store_acceleration(s, r, i, a);
      if constexpr (Solids) {
        double Lsum[9];
        for (int c = 0; c < 9; ++c) Lsum[c] = r.grad_v[9 * i + c];
        store_stress_rate<Dim>(s, r, i, Lsum);
      }
    }
  }
}
} // namespace

void sum_pairs(const Hydro& s, Rates& r, bool solids) {
  const int n = s.particles.owned_count();
  if (!s.settings.deterministic && s.neighbours.half_pairs.rows() != n)
    fail("SPH: the half neighbour list is not built for these particles (refresh_neighbours "
         "builds it)");
  const bool half = !s.settings.deterministic;
  const SimdTarget target = simd_target();
  switch (2 * (s.dim - 1) + (solids ? 1 : 0)) {
  case 0:
    return half ? half_rows<1, false>(s, r, target) : full_rows<1, false>(s, r, target);
  case 1:
    return half ? half_rows<1, true>(s, r, target) : full_rows<1, true>(s, r, target);
  case 2:
    return half ? half_rows<2, false>(s, r, target) : full_rows<2, false>(s, r, target);
  case 3:
    return half ? half_rows<2, true>(s, r, target) : full_rows<2, true>(s, r, target);
  case 4:
    return half ? half_rows<3, false>(s, r, target) : full_rows<3, false>(s, r, target);
  default:
    return half ? half_rows<3, true>(s, r, target) : full_rows<3, true>(s, r, target);
  }
}

} // namespace mf::sph
