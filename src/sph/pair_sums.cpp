#include "meshfree/sph/pair_sums.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/sph/pair_kernel.hpp"
#include <algorithm>
#include <cmath>
#include <omp.h>
#include <vector>

namespace mf::sph {

namespace {
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

/// The interacting pairs of row i of `list`, in the row's order; returns their count. The test and
/// the gradient are pair_gradient's, so every rate loop sums the same terms in the same order as
/// one walking the list with pair_gradient. Dim: the model's dimension; the coordinates beyond
/// it are zero for every particle, so their terms (exact zeros) are left out.
template <int Dim>
int live_pairs(const Hydro& s, const neighbors::PairList& list, const std::vector<double>& x, int i,
               LivePairs& live) {
  const long begin = list.offset[i], end = list.offset[i + 1];
  live.reserve(static_cast<std::size_t>(end - begin));
  const double* h = s.fields.h.data();
  const double xi[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
  int count = 0;
  // Without a branch: every pair is written at the next free slot, which advances only for an
  // interacting pair (about half of the list is the skin, in no predictable pattern).
  for (long k = begin; k < end; ++k) {
    const int j = list.partner[k];
    const double d0 = xi[0] - x[3 * j];
    const double d1 = Dim > 1 ? xi[1] - x[3 * j + 1] : 0.0;
    const double d2 = Dim > 2 ? xi[2] - x[3 * j + 2] : 0.0;
    double r2 = d0 * d0;
    if constexpr (Dim > 1) r2 += d1 * d1;
    if constexpr (Dim > 2) r2 += d2 * d2;
    const double hij = 0.5 * (h[i] + h[j]);
    live.j[count] = j;
    live.x0[count] = d0;
    if constexpr (Dim > 1) live.x1[count] = d1;
    if constexpr (Dim > 2) live.x2[count] = d2;
    live.r2[count] = r2, live.h[count] = hij;
    count += !(r2 >= 4.0 * hij * hij) & (r2 != 0.0);
  }
  kernel_slopes<Dim>(s.settings.kernel, live, count);
  return count;
}

/// Monaghan's artificial viscosity Pi_ij of pairs [0, count) of particle i (Monaghan 1992, eq.
/// 4.2): mu = h_ij v_ij.x_ij / (r^2 + (phi h_ij)^2), Pi = (-alpha c_ij mu + beta mu^2) / rho_ij
/// for approaching pairs (v_ij.x_ij < 0), else 0. The partners' values are gathered first so that
/// the arithmetic, two divisions a pair, runs as one packed loop with a select for the sign test.
template <int Dim> void viscosities(const Hydro& s, int i, LivePairs& live, int count) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const Settings& S = s.settings;
  for (int t = 0; t < count; ++t) {
    const int j = live.j[t];
    double vx = (P.v[3 * i] - P.v[3 * j]) * live.x0[t];
    if constexpr (Dim > 1) vx += (P.v[3 * i + 1] - P.v[3 * j + 1]) * live.x1[t];
    if constexpr (Dim > 2) vx += (P.v[3 * i + 2] - P.v[3 * j + 2]) * live.x2[t];
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

/// x_ij of slot t of `live`, with zeros beyond the model's dimension.
template <int Dim> inline void separation(const LivePairs& live, int t, double xij[3]) {
  xij[0] = live.x0[t];
  xij[1] = Dim > 1 ? live.x1[t] : 0.0;
  xij[2] = Dim > 2 ? live.x2[t] : 0.0;
}

/// gradient_vector over the model's Dim axes: g x_ij, or g A x_ij for the 3x3 correction A
/// (row-major); components beyond Dim are zero, as are the terms left out.
template <int Dim>
inline void gradient_along(const double* A, double g, const double xij[3], double out[3]) {
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

/// Velocity gradient L_i = sum_j (m_j / rho_j)(v_j - v_i) (x) grad_i W_ij of particle i over its
/// interacting pairs (row-major, L_ab = d v_a / d x_b; rows and columns beyond Dim stay zero).
template <int Dim>
void velocity_gradient(const Hydro& s, const Rates& r, int i, const LivePairs& live, int count,
                       double L[9]) {
  const particles::ParticleSet& P = s.particles;
  const double* C =
      s.settings.gradient_correction ? &r.correction[9 * static_cast<std::size_t>(i)] : nullptr;
  for (int c = 0; c < 9; ++c) L[c] = 0.0;
  for (int t = 0; t < count; ++t) {
    const int j = live.j[t];
    double xij[3], gv[3];
    separation<Dim>(live, t, xij);
    gradient_along<Dim>(C, live.g[t], xij, gv);
    const double vol = r.volume[j];
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) L[3 * a + b] += vol * (P.v[3 * j + a] - P.v[3 * i + a]) * gv[b];
  }
}

/// The Jaumann rate of a deviatoric stress S (Voigt: xx yy zz yz xz xy) under the velocity
/// gradient L with shear modulus G: dS = 2 G dev D + W S - S W, D and W the symmetric and
/// antisymmetric parts of L.
void jaumann_rate(const double L[9], const double s6[6], double G, double out[6]) {
  double D[3][3], W[3][3], Si[3][3];
  const double Sm[3][3] = {{s6[0], s6[5], s6[4]}, {s6[5], s6[1], s6[3]}, {s6[4], s6[3], s6[2]}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      D[a][b] = 0.5 * (L[3 * a + b] + L[3 * b + a]);
      W[a][b] = 0.5 * (L[3 * a + b] - L[3 * b + a]);
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
  out[0] = dS[0][0], out[1] = dS[1][1], out[2] = dS[2][2];
  out[3] = dS[1][2], out[4] = dS[0][2], out[5] = dS[0][1];
}

/// What pair (i, j) (slot t of `live`) contributes to the momentum, continuity and energy
/// equations before the partner's mass is applied (the thesis' eqs. 3-41, 3-48 and 3-64):
/// the pair's kernel gradient gv, q = p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij, v_ij . gv and, for
/// solids, the stress term T gv with T = S_i / rho_i^2 + S_j / rho_j^2 (+ the artificial stress)
/// and v_ij . T gv. Each of them is symmetric in i and j or changes sign with x_ij, bit for bit,
/// so one evaluation serves both ends of the pair. Components beyond Dim are zero: the motion
/// and the shear stresses out of the model's plane or line are (the terms left out are zeros).
/// The values of a row's own particle i that every pair of the row reads, gathered once per row
/// (the pair loops store through pointers the compiler cannot tell apart from these arrays, so
/// it would read them again after every store).
struct RowParticle {
  int i;
  double v[3], p_rho2, mass, volume, spacing;
  double T[6];     // S_i / rho_i^2 (solids)
  const double* C; // the correction matrix, or null
  const double* R; // the artificial stress, or null
  int material;
};

template <bool Solids> RowParticle row_particle(const Hydro& s, const Rates& r, int i) {
  const std::size_t k = static_cast<std::size_t>(i);
  RowParticle o;
  o.i = i;
  for (int d = 0; d < 3; ++d) o.v[d] = s.particles.v[3 * k + d];
  o.p_rho2 = r.p_rho2[k];
  o.mass = s.particles.mass[k];
  o.volume = r.volume[k];
  const bool spaced = s.settings.artificial_stress > 0.0 || s.settings.penalty.pressure > 0.0;
  o.spacing = spaced ? r.spacing[k] : 0.0;
  if constexpr (Solids)
    for (int c = 0; c < 6; ++c) o.T[c] = s.fields.S[6 * k + c] * r.inv_rho2[k];
  o.C = s.settings.gradient_correction ? &r.correction[9 * k] : nullptr;
  o.R = s.settings.artificial_stress > 0.0 ? &r.art_stress[6 * k] : nullptr;
  o.material = s.particles.material[k];
  return o;
}

struct PairTerms {
  double xij[3], vij[3], gv[3], q, vg;
  double Tg[3], vTg; // solids
  bool penalty;      // the inter-material penalty acts: force `push` along x_ij / r
  double push, r;
};

template <int Dim, bool Solids>
[[gnu::always_inline]] inline void pair_terms(const Hydro& s, const Rates& r, const RowParticle& o,
                                              int t, const LivePairs& live, PairTerms& p) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const Settings& S = s.settings;
  const int j = live.j[t];
  separation<Dim>(live, t, p.xij);
  const double r2 = live.r2[t], g = live.g[t], hij = live.h[t];
  for (int d = 0; d < 3; ++d) p.vij[d] = d < Dim ? o.v[d] - P.v[3 * j + d] : 0.0;
  p.q = o.p_rho2 + r.p_rho2[j] + live.visc[t];
  // The pair's gradient: with the correction, (C_i + C_j)/2 grad W, which stays antisymmetric
  // in i and j, so momentum is still conserved exactly.
  if (S.gradient_correction) {
    double A[9];
    const double* ci = o.C;
    const double* cj = &r.correction[9 * static_cast<std::size_t>(j)];
    for (int c = 0; c < 9; ++c) A[c] = 0.5 * (ci[c] + cj[c]);
    gradient_along<Dim>(A, g, p.xij, p.gv);
  } else {
    gradient_along<Dim>(nullptr, g, p.xij, p.gv);
  }
  p.vg = p.vij[0] * p.gv[0];
  for (int d = 1; d < Dim; ++d) p.vg += p.vij[d] * p.gv[d];
  if constexpr (Solids) {
    // Deviatoric stress: dv_i += m_j (S_i/rho_i^2 + S_j/rho_j^2) . grad W and
    // de_i -= m_j / 2 (S_i/rho_i^2 + S_j/rho_j^2) : (v_ij (x) grad W).
    const double* sj = &F.S[6 * static_cast<std::size_t>(j)];
    const double rj2 = r.inv_rho2[j];
    double T[6];
    for (int c = 0; c < 6; ++c) T[c] = o.T[c] + sj[c] * rj2;
    if (o.R) {
      // f^n (R_i + R_j), f = W(r) / W(dp) with dp the pair's mean initial spacing.
      const double dp = 0.5 * (o.spacing + r.spacing[j]);
      const double f = kernels::sph_kernel(S.kernel, s.dim, std::sqrt(r2), hij) /
                       kernels::sph_kernel(S.kernel, s.dim, dp, hij);
      const double fn = std::pow(f, S.artificial_stress_exponent);
      const double* Ri = o.R;
      const double* Rj = &r.art_stress[6 * static_cast<std::size_t>(j)];
      for (int c = 0; c < 6; ++c) T[c] += fn * (Ri[c] + Rj[c]);
    }
    // T gv with T symmetric (Voigt xx yy zz yz xz xy), over the first Dim rows and columns.
    const double* gx = p.gv;
    const int voigt[3][3] = {{0, 5, 4}, {5, 1, 3}, {4, 3, 2}};
    for (int a = 0; a < 3; ++a) {
      if (a >= Dim) {
        p.Tg[a] = 0.0;
        continue;
      }
      double sum = T[voigt[a][0]] * gx[0];
      for (int b = 1; b < Dim; ++b) sum += T[voigt[a][b]] * gx[b];
      p.Tg[a] = sum;
    }
    p.vTg = p.vij[0] * p.Tg[0];
    for (int d = 1; d < Dim; ++d) p.vTg += p.vij[d] * p.Tg[d];
  }
  p.penalty = false;
  if (S.penalty.pressure > 0.0 && o.material != P.material[j]) {
    const double a = 0.5 * (o.spacing + r.spacing[j]);
    const double r0 = S.penalty.distance * a, rr = std::sqrt(r2);
    if (rr < r0) {
      const double pe = r0 / rr;
      p.penalty = true;
      p.push = S.penalty.pressure * std::pow(a, s.dim - 1) *
               (std::pow(pe, S.penalty.n1) - std::pow(pe, S.penalty.n2));
      p.r = rr;
    }
  }
}

/// Adds gravity and damping (a += g - c v) to an owned particle's acceleration and stores it,
/// or 0 for a fixed particle.
inline void store_acceleration(const Hydro& s, Rates& r, int i, double acc[3]) {
  if (s.fields.fixed[i]) {
    for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = 0.0;
    return;
  }
  const double* v = &s.particles.v[3 * static_cast<std::size_t>(i)];
  if (s.gravity[0] != 0.0 || s.gravity[1] != 0.0 || s.gravity[2] != 0.0 || s.damping > 0.0) {
    const double damping = std::max(s.damping, 0.0);
    for (int d = 0; d < 3; ++d) acc[d] += s.gravity[d] - damping * v[d];
  }
  for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = acc[d];
}

/// The velocity gradient and Jaumann rate of owned particle i from its summed L; particles
/// without strength keep zeros.
inline void store_stress_rate(const Hydro& s, Rates& r, int i, const double L[9]) {
  double* grad = &r.grad_v[9 * static_cast<std::size_t>(i)];
  double* dS = &r.dS[6 * static_cast<std::size_t>(i)];
  if (r.shear[i] < 0.0) {
    for (int c = 0; c < 9; ++c) grad[c] = 0.0;
    for (int c = 0; c < 6; ++c) dS[c] = 0.0;
    return;
  }
  for (int c = 0; c < 9; ++c) grad[c] = L[c];
  jaumann_rate(L, &s.fields.S[6 * static_cast<std::size_t>(i)], r.shear[i], dS);
}

/// Deterministic sums (settings.deterministic): every owned particle sums its whole row in the
/// row's order (increasing global id, mirror images after), so its rates do not depend on the
/// threads or the ranks; each pair is evaluated from both ends.
template <int Dim, bool Solids> void full_rows(const Hydro& s, Rates& r) {
  const particles::ParticleSet& P = s.particles;
  const int n = P.owned_count();
#pragma omp parallel
  {
    LivePairs live;
    PairTerms p;
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < n; ++i) {
      const int count = live_pairs<Dim>(s, s.pairs, r.x, i, live);
      if constexpr (Solids) {
        double L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        if (r.shear[i] >= 0.0) velocity_gradient<Dim>(s, r, i, live, count, L);
        store_stress_rate(s, r, i, L);
      }
      viscosities<Dim>(s, i, live, count);
      const RowParticle o = row_particle<Solids>(s, r, i);
      double acc[3] = {0.0, 0.0, 0.0}, drho = 0.0, de = 0.0;
      for (int t = 0; t < count; ++t) {
        pair_terms<Dim, Solids>(s, r, o, t, live, p);
        const double mj = P.mass[live.j[t]];
        for (int d = 0; d < Dim; ++d) acc[d] -= mj * p.q * p.gv[d];
        drho += mj * p.vg;
        de += 0.5 * mj * p.q * p.vg;
        if constexpr (Solids) {
          for (int d = 0; d < Dim; ++d) acc[d] += mj * p.Tg[d];
          de -= 0.5 * mj * p.vTg;
        }
        if (p.penalty)
          for (int d = 0; d < Dim; ++d) acc[d] += p.push / o.mass * p.xij[d] / p.r;
      }
      store_acceleration(s, r, i, acc);
      r.drho[i] = drho;
      r.de[i] = de;
    }
  }
}

/// Each pair once, Newton's third law (the default): the half list holds partner j > i only, and
/// the pair's terms go to both ends. Thread t takes rows [first_row[t], first_row[t + 1]) with an
/// equal share of the pairs; its reactions on partners land in its own buffer over
/// [first_row[t], owned) (thread 0 writes the outputs directly), and the buffers are added in
/// thread order afterwards. A pair with a ghost (another rank's particle, a mirror image) gives
/// its terms to the owned particle only; the ghost's owner sums its own side. The sums run in an
/// order that depends on the threads and ranks.
template <int Dim, bool Solids> void half_rows(const Hydro& s, Rates& r) {
  const particles::ParticleSet& P = s.particles;
  const int n = P.owned_count();
  const neighbors::PairList& half = s.half_pairs;
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
    PairTerms p;
    for (int i = lo; i < hi; ++i) {
      const int count = live_pairs<Dim>(s, half, r.x, i, live);
      viscosities<Dim>(s, i, live, count);
      const RowParticle o = row_particle<Solids>(s, r, i);
      const double mi = o.mass, vol_i = o.volume;
      const bool corrected = s.settings.gradient_correction;
      const double* Ci = o.C;
      double ai[3] = {0.0, 0.0, 0.0}, drho_i = 0.0, de_i = 0.0;
      double Li[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      for (int k = 0; k < count; ++k) {
        pair_terms<Dim, Solids>(s, r, o, k, live, p);
        const int j = live.j[k];
        const double mj = P.mass[j];
        for (int d = 0; d < Dim; ++d) ai[d] -= mj * p.q * p.gv[d];
        drho_i += mj * p.vg;
        de_i += 0.5 * mj * p.q * p.vg;
        // The velocity gradient's kernel gradients: C_i g x_ij for i and, for j, C_j g x_ij
        // (grad_j W_ji = -g x_ij and v_j - v_i = -v_ij: the signs cancel); without the
        // correction both are the pair's gv.
        double gi[3], gj[3];
        if constexpr (Solids) {
          for (int d = 0; d < Dim; ++d) ai[d] += mj * p.Tg[d];
          de_i -= 0.5 * mj * p.vTg;
          const double* gl = p.gv;
          if (corrected) {
            gradient_along<Dim>(Ci, live.g[k], p.xij, gi);
            gl = gi;
          }
          const double vol_j = r.volume[j];
          for (int a = 0; a < Dim; ++a)
            for (int b = 0; b < Dim; ++b) Li[3 * a + b] -= vol_j * p.vij[a] * gl[b];
        }
        if (p.penalty)
          for (int d = 0; d < Dim; ++d) ai[d] += p.push / mi * p.xij[d] / p.r;
        if (j >= n) continue; // a ghost: its owner sums its side
        // Partner j: x_ji = -x_ij and v_ji = -v_ij, so gv and T gv change sign while q, v.gv and
        // v.T gv do not.
        const std::size_t jb = static_cast<std::size_t>(j - base);
        double* aj = &acc[3 * jb];
        for (int d = 0; d < Dim; ++d) aj[d] += mi * p.q * p.gv[d];
        drho[jb] += mi * p.vg;
        de[jb] += 0.5 * mi * p.q * p.vg;
        if constexpr (Solids) {
          for (int d = 0; d < Dim; ++d) aj[d] -= mi * p.Tg[d];
          de[jb] -= 0.5 * mi * p.vTg;
          const double* gl = p.gv;
          if (corrected) {
            const double* Cj = &r.correction[9 * static_cast<std::size_t>(j)];
            gradient_along<Dim>(Cj, live.g[k], p.xij, gj);
            gl = gj;
          }
          double* Lj = &L[9 * jb];
          for (int a = 0; a < Dim; ++a)
            for (int b = 0; b < Dim; ++b) Lj[3 * a + b] -= vol_i * p.vij[a] * gl[b];
        }
        if (p.penalty)
          for (int d = 0; d < Dim; ++d) aj[d] -= p.push / P.mass[j] * p.xij[d] / p.r;
      }
      const std::size_t ib = static_cast<std::size_t>(i - base);
      for (int d = 0; d < 3; ++d) acc[3 * ib + d] += ai[d];
      drho[ib] += drho_i;
      de[ib] += de_i;
      if constexpr (Solids)
        for (int c = 0; c < 9; ++c) L[9 * ib + c] += Li[c];
    }
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
        store_stress_rate(s, r, i, Lsum);
      }
    }
  }
}
} // namespace

void sum_pairs(const Hydro& s, Rates& r, bool solids) {
  const int n = s.particles.owned_count();
  if (!s.settings.deterministic && s.half_pairs.rows() != n)
    fail("SPH: the half neighbour list is not built for these particles (refresh_neighbours "
         "builds it)");
  const bool half = !s.settings.deterministic;
  switch (2 * (s.dim - 1) + (solids ? 1 : 0)) {
  case 0:
    return half ? half_rows<1, false>(s, r) : full_rows<1, false>(s, r);
  case 1:
    return half ? half_rows<1, true>(s, r) : full_rows<1, true>(s, r);
  case 2:
    return half ? half_rows<2, false>(s, r) : full_rows<2, false>(s, r);
  case 3:
    return half ? half_rows<2, true>(s, r) : full_rows<2, true>(s, r);
  case 4:
    return half ? half_rows<3, false>(s, r) : full_rows<3, false>(s, r);
  default:
    return half ? half_rows<3, true>(s, r) : full_rows<3, true>(s, r);
  }
}

} // namespace mf::sph
