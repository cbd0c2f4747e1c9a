// The packed bond rows of pd/bond_rows.hpp (x86-64): each row in blocks of 16 bonds, first the
// partners' positions and the classes' constants as columns (one load of four doubles per bond,
// transposed four bonds at a time), then every bond's stretch, force factors and breaking test
// as one plain loop over the columns, which GCC vectorises for the target it is compiled for
// (AVX2: four lanes, AVX-512: eight), then the sums over the block in bond order. The file is
// compiled without contraction (no FMA) and without errno for sqrt (CMakeLists.txt): each bond
// is computed with the IEEE operations of the scalar rows, in the same order, so that the
// results equal theirs bit for bit.
#include "meshfree/pd/bond_rows.hpp"
#if defined(__x86_64__) && defined(__GNUC__)
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <immintrin.h>
#include <limits>

#define MF_TARGET_AVX2 __attribute__((target("avx2")))
#define MF_TARGET_AVX512                                                                           \
  __attribute__((target("avx2,avx512f,avx512vl,avx512bw,avx512dq,avx512cd,prefer-vector-width=512")))
#define MF_ALWAYS_INLINE __attribute__((always_inline)) inline

namespace mf::pd::rows {
namespace {

/// Bonds per block, a multiple of every target's lanes (16 of 32 bits with AVX-512): the
/// packed pass runs a fixed count, with no scalar remainder.
constexpr int kBlock = 16;

/// What the packed pass reads for a block: the bonds' own arrays, past the row's end into the
/// next rows where they hold a whole block (the extra bonds are computed and not summed), else
/// a copy of the row's last bonds padded with its last bond. Plastic stretches past the row,
/// which another thread may be writing, are not read.
struct BlockInput {
  const int* partner;
  const std::uint32_t* cls;
  const double* plastic;
};

/// What the packed pass leaves for each bond of a block.
struct Block {
  alignas(64) double fi[3][kBlock]; // force density on i, c w_ij g (y_j - y_i)
  alignas(64) double fj[3][kBlock]; // half layout: its reaction's magnitude on j, c w_ji g (...)
  alignas(64) double wi[kBlock];    // energy: c w_ij w / 2 (w the bond's energy density)
  alignas(64) double wj[kBlock];    // half layout: c w_ji w / 2
  alignas(64) double ej[kBlock];    // half layout: V_j c w_ji w / 2
  alignas(64) double candidate[kBlock]; // alpha rule: s00 - alpha s
  alignas(64) double plastic[kBlock];   // micro-plastic: the plastic stretch after the bond
  alignas(64) int breaks[kBlock];
  // The block's inputs as columns: partners' positions, class constants, the partners' s0.
  alignas(64) double yj[3][kBlock];
  alignas(64) double length[kBlock];
  alignas(64) double inv_length[kBlock];
  alignas(64) double cw[kBlock];
  alignas(64) double cw_partner[kBlock];
  alignas(64) double s0j[kBlock];
};

static_assert(offsetof(BondClass, inv_length) == offsetof(BondClass, length) + 8 &&
                  offsetof(BondClass, cw) == offsetof(BondClass, length) + 16 &&
                  offsetof(BondClass, cw_partner) == offsetof(BondClass, length) + 24,
              "the four constants read per bond lie side by side");

/// Four rows of four doubles as four columns.
MF_TARGET_AVX2 MF_ALWAYS_INLINE void transpose(__m256d r[4]) {
  const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
  const __m256d t2 = _mm256_unpacklo_pd(r[2], r[3]), t3 = _mm256_unpackhi_pd(r[2], r[3]);
  r[0] = _mm256_permute2f128_pd(t0, t2, 0x20), r[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  r[2] = _mm256_permute2f128_pd(t0, t2, 0x31), r[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

/// columns() with one load of four doubles per bond for the position (past the last position
/// the fourth masked off) and one for the class constants, turned into columns four bonds at a
/// time. The arrays are read into locals once: a vector store might alias any.
template <bool Alpha> MF_TARGET_AVX2 void columns_avx2(const Arrays& a, const BlockInput& in, Block& b) {
  const __m256i xyz = _mm256_set_epi64x(0, -1, -1, -1);
  const double* const y = a.y;
  const double* const s0 = a.s0;
  const BondClass* const classes = a.classes;
  const int* const partner = in.partner;
  const std::uint32_t* const cls = in.cls;
  const int last = a.points - 1;
  for (int l = 0; l < kBlock; l += 4) {
    __m256d p[4], c[4];
    for (int q = 0; q < 4; ++q) {
      const int j = partner[l + q];
      p[q] = j < last ? _mm256_loadu_pd(y + 3 * j) : _mm256_maskload_pd(y + 3 * j, xyz);
      c[q] = _mm256_loadu_pd(&classes[cls[l + q]].length);
      if constexpr (Alpha) b.s0j[l + q] = s0[j];
    }
    transpose(p);
    transpose(c);
    for (int d = 0; d < 3; ++d) _mm256_store_pd(b.yj[d] + l, p[d]);
    _mm256_store_pd(b.length + l, c[0]), _mm256_store_pd(b.inv_length + l, c[1]);
    _mm256_store_pd(b.cw + l, c[2]), _mm256_store_pd(b.cw_partner + l, c[3]);
  }
}

/// The padded copy of a row's last bonds.
struct Padded {
  alignas(64) int partner[kBlock];
  alignas(64) std::uint32_t cls[kBlock];
  alignas(64) double plastic[kBlock];
};

/// The input of the block of bonds k0 .. k0 + len - 1.
template <bool Plastic>
MF_ALWAYS_INLINE BlockInput block_input(const Arrays& a, long k0, int len, Padded& pad) {
  if (len == kBlock || (!Plastic && k0 + kBlock <= a.offset[a.owned]))
    return {a.partner + k0, a.cls + k0, Plastic ? a.plastic + k0 : nullptr};
  for (int l = 0; l < kBlock; ++l) {
    const long k = k0 + std::min(l, len - 1);
    pad.partner[l] = a.partner[k], pad.cls[l] = a.cls[k];
    if constexpr (Plastic) pad.plastic[l] = a.plastic[k];
  }
  return {pad.partner, pad.cls, pad.plastic};
}

/// The critical stretch of a bond: the law's, or with the LAMMPS rule min(s0_i, s0_j) of the
/// previous evaluation (pair_peri_pmb.cpp, PairPeriPMB::compute) where the law breaks. `c`
/// holds the law's constants.
template <bool Alpha>
MF_ALWAYS_INLINE double critical(const BondClass& c, double s0_j, double s0_i) {
  if constexpr (Alpha) { // std::max(std::min(s0_i, s0_j), floor) on values, not references
    const double floor = c.alpha_floor;
    const double lower = s0_j < s0_i ? s0_j : s0_i;
    return lower < floor ? floor : lower;
  }
  else
    return c.limit;
}

/// The packed pass over a block of bonds of the row of the particle at yi.
/// With the stretch s = |y_j - y_i| / |xi| - 1 and the plastic stretch s_p (Macek & Silling
/// 2007: |s - s_p| <= s_Y, the return is exact), the force density on i is
/// c w_ij (s - s_p) (y_j - y_i) / |y_j - y_i| (Silling & Askari 2005, eq. 3 and 6; LAMMPS
/// pair_peri_pmb.cpp, PairPeriPMB::compute, computes dr = r - r0 the same way); the class holds
/// c w_ij and 1 / |xi|, so that the bond costs a square root and one division. A broken bond is
/// computed too (no branch), and left out by the sums.
/// OneLaw: every class has the law constants of a.law, read once instead of per bond.
template <bool Half, bool Plastic, bool Alpha, bool Energy, bool OneLaw>
MF_ALWAYS_INLINE void evaluate(const Arrays& a, const double* yi, double s0_i, const BlockInput& in,
                               Block& b) {
  const double x0 = yi[0], x1 = yi[1], x2 = yi[2];
  const double* const plastic = in.plastic;
  const double* const volume = a.volume;
  const int* const partner = in.partner;
  for (int l = 0; l < kBlock; ++l) {
    const BondClass& law = OneLaw ? *a.law : a.classes[in.cls[l]];
    const double dx = b.yj[0][l] - x0, dy = b.yj[1][l] - x1, dz = b.yj[2][l] - x2;
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double inv_r = r > 0.0 ? 1.0 / r : 0.0;
    const double s = (r - b.length[l]) * b.inv_length[l]; // r - |xi| exact near |xi| (Sterbenz)
    double e = s;
    if constexpr (Plastic) {
      const double before = plastic[l], elastic = s - before;
      const double sp = elastic > law.yield    ? s - law.yield
                        : elastic < -law.yield ? s + law.yield
                                               : before;
      b.plastic[l] = sp;
      e = s - sp;
    }
    // Each layout's own order of the products (half: c w (e / r); full: (c w e) / r), which
    // the scalar loop of that layout has.
    const double g = e * inv_r;
    const double gi = Half ? b.cw[l] * g : b.cw[l] * e * inv_r;
    b.fi[0][l] = gi * dx, b.fi[1][l] = gi * dy, b.fi[2][l] = gi * dz;
    if constexpr (Half) {
      const double gj = b.cw_partner[l] * g;
      b.fj[0][l] = gj * dx, b.fj[1][l] = gj * dy, b.fj[2][l] = gj * dz;
    }
    if constexpr (Energy) {
      // w = c (s - s_p)^2 |xi| / 2 per bond, half of it to each end.
      const double half_w = 0.25 * e * e * b.length[l];
      b.wi[l] = b.cw[l] * half_w;
      if constexpr (Half)
        b.wj[l] = b.cw_partner[l] * half_w,
        b.ej[l] = volume[partner[l]] * b.cw_partner[l] * half_w;
    }
    // LAMMPS: s0 follows the most compressed intact bond, s00 - alpha s.
    if constexpr (Alpha) b.candidate[l] = law.s00 - law.alpha * s;
    b.breaks[l] = s > critical<Alpha>(law, b.s0j[l], s0_i);
  }
}

/// Micro-plastic: the plastic stretches of the intact bonds of a block, after it.
MF_ALWAYS_INLINE void store_plastic(const Arrays& a, long k0, int len, const Block& b) {
  for (int l = 0; l < len; ++l)
    if (a.intact[k0 + l]) a.plastic[k0 + l] = b.plastic[l];
}

/// The running sums of one row.
struct RowSums {
  double f[3] = {0.0, 0.0, 0.0};
  double w = 0.0;
  double s0 = -std::numeric_limits<double>::infinity();
};

/// Half layout: the sums of a block in bond order; reactions on owned partners to `out`. The
/// arrays are read into locals once: a store of a byte (a broken bond) might alias any.
template <bool Plastic, bool Alpha, bool Energy>
MF_ALWAYS_INLINE void add_half(const Arrays& a, long k0, int len, const Block& b, const Output& out,
                               RowSums& row, Sums& sums) {
  unsigned char* const intact = a.intact + k0;
  const int* const partner = a.partner + k0;
  const int owned = a.owned, base = out.base;
  double* const f = out.f;
  double* const w = out.w;
  double* const s0n = out.s0n;
  for (int l = 0; l < len; ++l) {
    if (!intact[l]) continue;
    for (int d = 0; d < 3; ++d) row.f[d] += b.fi[d][l];
    const int j = partner[l];
    const bool j_owned = j < owned;
    const std::ptrdiff_t jb = j - base;
    if (j_owned)
      for (int d = 0; d < 3; ++d) f[3 * jb + d] -= b.fj[d][l];
    if constexpr (Energy) {
      row.w += b.wi[l];
      if (j_owned) {
        sums.energy += b.ej[l];
        if (w) w[jb] += b.wj[l];
      }
    }
    if constexpr (Alpha) {
      row.s0 = std::max(row.s0, b.candidate[l]);
      if (j_owned) s0n[jb] = std::max(s0n[jb], b.candidate[l]);
    }
    if (b.breaks[l]) {
      intact[l] = 0;
      sums.broken += j_owned ? 2 : 1;
    }
  }
}

/// Full layout: the sums of a block in bond order.
template <bool Plastic, bool Alpha, bool Energy>
MF_ALWAYS_INLINE void add_full(const Arrays& a, long k0, int len, const Block& b, RowSums& row,
                               Sums& sums) {
  unsigned char* const intact = a.intact + k0;
  for (int l = 0; l < len; ++l) {
    if (!intact[l]) continue;
    for (int d = 0; d < 3; ++d) row.f[d] += b.fi[d][l];
    if constexpr (Energy) row.w += b.wi[l];
    if constexpr (Alpha) row.s0 = std::max(row.s0, b.candidate[l]);
    if (b.breaks[l]) {
      intact[l] = 0;
      ++sums.broken;
    }
  }
}

/// Rows [lo, hi) of either layout, in blocks of kBlock bonds.
template <bool Half, bool Plastic, bool Alpha, bool Energy>
MF_ALWAYS_INLINE Sums run_rows(const Arrays& a, int lo, int hi, const Output& out) {
  Block b;
  Padded pad;
  Sums sums;
  for (int i = lo; i < hi; ++i) {
    const double s0_i = Alpha ? a.s0[i] : 0.0;
    RowSums row;
    for (long k0 = a.offset[i]; k0 < a.offset[i + 1]; k0 += kBlock) {
      const int len = static_cast<int>(std::min<long>(kBlock, a.offset[i + 1] - k0));
      const BlockInput in = block_input<Plastic>(a, k0, len, pad);
      columns_avx2<Alpha>(a, in, b);
      if (a.law)
        evaluate<Half, Plastic, Alpha, Energy, true>(a, &a.y[3 * i], s0_i, in, b);
      else
        evaluate<Half, Plastic, Alpha, Energy, false>(a, &a.y[3 * i], s0_i, in, b);
      if constexpr (Plastic) store_plastic(a, k0, len, b);
      if constexpr (Half)
        add_half<Plastic, Alpha, Energy>(a, k0, len, b, out, row, sums);
      else
        add_full<Plastic, Alpha, Energy>(a, k0, len, b, row, sums);
    }
    const std::ptrdiff_t ib = i - out.base;
    if constexpr (Half) {
      for (int d = 0; d < 3; ++d) out.f[3 * ib + d] += row.f[d];
      if constexpr (Energy) {
        sums.energy += a.volume[i] * row.w;
        if (out.w) out.w[ib] += row.w;
      }
      if constexpr (Alpha) out.s0n[ib] = std::max(out.s0n[ib], row.s0);
    } else {
      for (int d = 0; d < 3; ++d) out.f[3 * ib + d] = row.f[d];
      if constexpr (Energy) out.w[ib] = row.w;
      if constexpr (Alpha) out.s0n[ib] = row.s0;
    }
  }
  return sums;
}

using RowsFn = Sums (*)(const Arrays&, int, int, const Output&);

template <bool H, bool P, bool A, bool E>
MF_TARGET_AVX2 Sums rows_avx2(const Arrays& a, int lo, int hi, const Output& out) {
  return run_rows<H, P, A, E>(a, lo, hi, out);
}

template <bool H, bool P, bool A, bool E>
MF_TARGET_AVX512 Sums rows_avx512(const Arrays& a, int lo, int hi, const Output& out) {
  return run_rows<H, P, A, E>(a, lo, hi, out);
}

template <bool H, bool P, bool A, bool E> RowsFn of_target(SimdTarget t) {
  return t == SimdTarget::Avx512 ? &rows_avx512<H, P, A, E> : &rows_avx2<H, P, A, E>;
}

template <bool H, bool P, bool A> RowsFn of_energy(Terms terms, SimdTarget t) {
  return terms.energy ? of_target<H, P, A, true>(t) : of_target<H, P, A, false>(t);
}

template <bool H> RowsFn of_terms(Terms terms, SimdTarget t) {
  if (terms.plastic)
    return terms.alpha ? of_energy<H, true, true>(terms, t) : of_energy<H, true, false>(terms, t);
  return terms.alpha ? of_energy<H, false, true>(terms, t) : of_energy<H, false, false>(terms, t);
}

} // namespace

Sums packed(const Arrays& a, Terms terms, bool half, SimdTarget target, int lo, int hi,
            const Output& out) {
  return (half ? of_terms<true>(terms, target) : of_terms<false>(terms, target))(a, lo, hi, out);
}

} // namespace mf::pd::rows
#endif
