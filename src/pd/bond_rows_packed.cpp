// The packed bond rows of pd/bond_rows.hpp (x86-64): each row in groups of four bonds. A group's
// four partners' positions (four doubles a point, pd/bond_rows.hpp) and four bond classes'
// constants are loaded one bond to a register and transposed into columns; the stretches, square
// roots, divisions, force factors and breaking tests are computed four bonds at a time; then the
// bonds, in order, add their forces (x, y, z in one register: the bond's y_j - y_i times its
// factor) to the row's sum and, in the half layout, take their reactions off their partners'
// forces (four doubles a point too: one load, subtraction and store each). The file is compiled
// without contraction (no FMA) and without errno for sqrt (CMakeLists.txt): each bond is computed
// with the IEEE operations of the scalar rows, in the same order, so that the results equal
// theirs bit for bit.
#include "meshfree/pd/bond_rows.hpp"
#if defined(__x86_64__) && defined(__GNUC__)
#include "packed_columns.hpp"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <immintrin.h>
#include <limits>

namespace mf::pd::rows {
namespace {

static_assert(offsetof(BondClass, inv_length) == offsetof(BondClass, length) + 8 &&
                  offsetof(BondClass, cw) == offsetof(BondClass, length) + 16 &&
                  offsetof(BondClass, cw_partner) == offsetof(BondClass, length) + 24,
              "the four constants read per bond lie side by side");

using packed::transpose;

/// A group of four bonds of a row: the bonds k0 .. k0 + 3, or where the row ends first, its
/// last bond in the lanes past the end (computed, never summed).
struct Group {
  long k[4];
  int j[4]; // partners
  const BondClass* c[4];
  __m256d d[4]; // y_j - y_i, a bond per register (the fourth lane zero)
};

/// The law's constants of a group as columns: the shared law's, or each bond's class's.
struct LawColumns {
  __m256d limit, floor, s00, alpha, yield;
};

template <bool OneLaw>
MF_TARGET_AVX2 MF_ALWAYS_INLINE LawColumns law_columns(const Arrays& a, const Group& g) {
  if constexpr (OneLaw) {
    const BondClass& l = *a.law;
    return {_mm256_set1_pd(l.limit), _mm256_set1_pd(l.alpha_floor), _mm256_set1_pd(l.s00),
            _mm256_set1_pd(l.alpha), _mm256_set1_pd(l.yield)};
  } else {
    const BondClass *c0 = g.c[0], *c1 = g.c[1], *c2 = g.c[2], *c3 = g.c[3];
    return {_mm256_set_pd(c3->limit, c2->limit, c1->limit, c0->limit),
            _mm256_set_pd(c3->alpha_floor, c2->alpha_floor, c1->alpha_floor, c0->alpha_floor),
            _mm256_set_pd(c3->s00, c2->s00, c1->s00, c0->s00),
            _mm256_set_pd(c3->alpha, c2->alpha, c1->alpha, c0->alpha),
            _mm256_set_pd(c3->yield, c2->yield, c1->yield, c0->yield)};
  }
}

/// What each bond of a group leaves for its turn in the row's order.
struct Factors {
  alignas(32) double gi[4];        // force on i over (y_j - y_i): c w_ij (s - s_p) / r
  alignas(32) double gj[4];        // half layout: its reaction's, c w_ji (s - s_p) / r
  alignas(32) double wi[4];        // energy: c w_ij w / 2 (w the bond's energy density)
  alignas(32) double wj[4];        // half layout: c w_ji w / 2
  alignas(32) double ej[4];        // half layout: V_j c w_ji w / 2
  alignas(32) double candidate[4]; // LAMMPS rule: s00 - alpha s
  alignas(32) double plastic[4];   // micro-plastic: the plastic stretch after the bond
  int breaks;                      // bit q set where bond q breaks
};

/// The group starting at bond k0 of a row ending at `end`, for the particle at yi; `cls` the
/// class indices (two or four bytes).
template <class Index>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void load_group(const Arrays& a, const Index* cls, long k0,
                                                long end, __m256d yi, Group& g) {
  for (int q = 0; q < 4; ++q) {
    const long k = std::min(k0 + q, end - 1);
    g.k[q] = k;
    g.j[q] = a.partner[k];
    g.c[q] = &a.classes[cls[k]];
    g.d[q] = _mm256_sub_pd(_mm256_load_pd(a.y + 4 * static_cast<std::ptrdiff_t>(g.j[q])), yi);
  }
}

/// The packed pass over a group of bonds of a row whose particle has s0 `s0_i` (LAMMPS rule).
/// With the stretch s = |y_j - y_i| / |xi| - 1 and the plastic stretch s_p (Macek & Silling
/// 2007: |s - s_p| <= s_Y, the return is exact), the force density on i is
/// c w_ij (s - s_p) (y_j - y_i) / |y_j - y_i| (Silling & Askari 2005, eq. 3 and 6; LAMMPS
/// pair_peri_pmb.cpp, PairPeriPMB::compute, computes dr = r - r0 the same way); the class holds
/// c w_ij and 1 / |xi|, so that the bond costs a square root and one division. A broken bond is
/// computed too (no branch), and left out by the sums.
template <bool Half, bool Plastic, bool Alpha, bool Energy, bool OneLaw>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void evaluate(const Arrays& a, const Group& g, __m256d s0_i,
                                              Factors& out) {
  __m256d x[4] = {g.d[0], g.d[1], g.d[2], g.d[3]};
  transpose(x); // dx, dy, dz, zero
  __m256d c[4];
  for (int q = 0; q < 4; ++q) c[q] = _mm256_loadu_pd(&g.c[q]->length);
  transpose(c); // |xi|, 1 / |xi|, c w_ij, c w_ji
  const LawColumns law = law_columns<OneLaw>(a, g);
  const __m256d r2 =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x[0], x[0]), _mm256_mul_pd(x[1], x[1])),
                    _mm256_mul_pd(x[2], x[2]));
  const __m256d r = _mm256_sqrt_pd(r2);
  const __m256d zero = _mm256_setzero_pd();
  const __m256d inv_r =
      _mm256_and_pd(_mm256_div_pd(_mm256_set1_pd(1.0), r), _mm256_cmp_pd(r, zero, _CMP_GT_OQ));
  const __m256d s = _mm256_mul_pd(_mm256_sub_pd(r, c[0]), c[1]); // r - |xi| exact near |xi|
  __m256d e = s;
  if constexpr (Plastic) {
    const __m256d before =
        _mm256_set_pd(a.plastic[g.k[3]], a.plastic[g.k[2]], a.plastic[g.k[1]], a.plastic[g.k[0]]);
    const __m256d elastic = _mm256_sub_pd(s, before);
    const __m256d minus_yield = _mm256_xor_pd(law.yield, _mm256_set1_pd(-0.0));
    const __m256d up = _mm256_cmp_pd(elastic, law.yield, _CMP_GT_OQ);
    const __m256d down = _mm256_cmp_pd(elastic, minus_yield, _CMP_LT_OQ);
    __m256d sp = _mm256_blendv_pd(before, _mm256_add_pd(s, law.yield), down);
    sp = _mm256_blendv_pd(sp, _mm256_sub_pd(s, law.yield), up);
    _mm256_store_pd(out.plastic, sp);
    e = _mm256_sub_pd(s, sp);
  }
  // Each layout's own order of the products (half: c w (e / r); full: (c w e) / r), which the
  // scalar rows of that layout have.
  if constexpr (Half) {
    const __m256d ge = _mm256_mul_pd(e, inv_r);
    _mm256_store_pd(out.gi, _mm256_mul_pd(c[2], ge));
    _mm256_store_pd(out.gj, _mm256_mul_pd(c[3], ge));
  } else {
    _mm256_store_pd(out.gi, _mm256_mul_pd(_mm256_mul_pd(c[2], e), inv_r));
  }
  if constexpr (Energy) {
    // w = c (s - s_p)^2 |xi| / 2 per bond, half of it to each end.
    const __m256d half_w =
        _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.25), e), e), c[0]);
    _mm256_store_pd(out.wi, _mm256_mul_pd(c[2], half_w));
    if constexpr (Half) {
      const double* v = a.volume;
      const __m256d vj = _mm256_set_pd(v[g.j[3]], v[g.j[2]], v[g.j[1]], v[g.j[0]]);
      _mm256_store_pd(out.wj, _mm256_mul_pd(c[3], half_w));
      _mm256_store_pd(out.ej, _mm256_mul_pd(_mm256_mul_pd(vj, c[3]), half_w));
    }
  }
  __m256d limit = law.limit;
  if constexpr (Alpha) {
    // LAMMPS: s0 follows the most compressed intact bond, s00 - alpha s; a bond breaks past
    // max(min(s0_i, s0_j), floor) of the previous evaluation (std::min and std::max exactly).
    _mm256_store_pd(out.candidate, _mm256_sub_pd(law.s00, _mm256_mul_pd(law.alpha, s)));
    const double* s0 = a.s0;
    const __m256d s0_j = _mm256_set_pd(s0[g.j[3]], s0[g.j[2]], s0[g.j[1]], s0[g.j[0]]);
    limit = _mm256_max_pd(law.floor, _mm256_min_pd(s0_j, s0_i));
  }
  out.breaks = _mm256_movemask_pd(_mm256_cmp_pd(s, limit, _CMP_GT_OQ));
}

/// The running sums of one row.
struct RowSums {
  __m256d f;
  double w = 0.0;
  double s0 = -std::numeric_limits<double>::infinity();
};

/// What the sums write, read into locals once: a store of a byte (a broken bond) might alias any.
struct Targets {
  unsigned char* intact;
  double* plastic;
  double* f;
  double* w;
  double* s0n;
  int owned, base;
};

inline Targets targets_of(const Arrays& a, const Output& out) {
  return {a.intact, a.plastic, out.f, out.w, out.s0n, a.owned, out.base};
}

/// Whether the four bonds from k are intact (flags 0 or 1).
MF_ALWAYS_INLINE bool four_intact(const unsigned char* intact, long k) {
  std::uint32_t flags;
  std::memcpy(&flags, intact + k, sizeof flags);
  return flags == 0x01010101u;
}

/// The sums of intact bond q of a group: its force to the row's, its reaction to an owned
/// partner's (half layout), its energies and s0 candidate.
template <bool Half, bool Alpha, bool Energy>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void add_bond(const Targets t, const Group& g, const Factors& b,
                                              int q, bool j_owned, RowSums& row, Sums& sums) {
  row.f = _mm256_add_pd(row.f, _mm256_mul_pd(_mm256_broadcast_sd(&b.gi[q]), g.d[q]));
  const std::ptrdiff_t jb = g.j[q] - t.base;
  if constexpr (Half)
    if (j_owned) {
      double* const fj = t.f + 4 * jb;
      const __m256d reaction = _mm256_mul_pd(_mm256_broadcast_sd(&b.gj[q]), g.d[q]);
      _mm256_store_pd(fj, _mm256_sub_pd(_mm256_load_pd(fj), reaction));
    }
  if constexpr (Energy) {
    row.w += b.wi[q];
    if (j_owned) {
      sums.energy += b.ej[q];
      if (t.w) t.w[jb] += b.wj[q];
    }
  }
  if constexpr (Alpha) {
    row.s0 = std::max(row.s0, b.candidate[q]);
    if (j_owned) t.s0n[jb] = std::max(t.s0n[jb], b.candidate[q]);
  }
}

/// The first `len` bonds of a group in order: the intact ones add to the sums (add_bond), the
/// ones past their limit break. A whole group of intact bonds none of which breaks, with owned
/// partners in the half layout, is taken without a test per bond.
template <bool Half, bool Plastic, bool Alpha, bool Energy>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void add(const Targets t, const Group& g, int len, const Factors& b,
                                         RowSums& row, Sums& sums) {
  if (len == 4 && !b.breaks && four_intact(t.intact, g.k[0]) &&
      (!Half || std::max(std::max(g.j[0], g.j[1]), std::max(g.j[2], g.j[3])) < t.owned)) {
    if constexpr (Plastic) _mm256_storeu_pd(t.plastic + g.k[0], _mm256_load_pd(b.plastic));
    for (int q = 0; q < 4; ++q) add_bond<Half, Alpha, Energy>(t, g, b, q, Half, row, sums);
    return;
  }
  for (int q = 0; q < len; ++q) {
    const long k = g.k[q];
    if (!t.intact[k]) continue;
    if constexpr (Plastic) t.plastic[k] = b.plastic[q];
    const bool j_owned = Half && g.j[q] < t.owned;
    add_bond<Half, Alpha, Energy>(t, g, b, q, j_owned, row, sums);
    if (b.breaks >> q & 1) {
      t.intact[k] = 0;
      sums.broken += j_owned ? 2 : 1;
    }
  }
}

/// A row's sums to its outputs: added (half layout, four doubles a point) or written (full).
template <bool Half, bool Alpha, bool Energy>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void write_row(const Arrays& a, int i, const RowSums& row,
                                               const Output& out, Sums& sums) {
  const std::ptrdiff_t ib = i - out.base;
  if constexpr (Half) {
    double* const fi = out.f + 4 * ib;
    _mm256_store_pd(fi, _mm256_add_pd(_mm256_load_pd(fi), row.f));
    if constexpr (Energy) {
      sums.energy += a.volume[i] * row.w;
      if (out.w) out.w[ib] += row.w;
    }
    if constexpr (Alpha) out.s0n[ib] = std::max(out.s0n[ib], row.s0);
  } else {
    alignas(32) double f[4];
    _mm256_store_pd(f, row.f);
    for (int d = 0; d < 3; ++d) out.f[3 * ib + d] = f[d];
    if constexpr (Energy) out.w[ib] = row.w;
    if constexpr (Alpha) out.s0n[ib] = row.s0;
  }
}

/// Rows [lo, hi) of either layout, in groups of four bonds.
template <bool Half, bool Plastic, bool Alpha, bool Energy, bool OneLaw, class Index>
MF_TARGET_AVX2 MF_ALWAYS_INLINE Sums run_rows(const Arrays& a, const Index* cls, int lo, int hi,
                                              const Output& out) {
  Sums sums;
  Group g;
  Factors b;
  const Targets t = targets_of(a, out);
  for (int i = lo; i < hi; ++i) {
    const __m256d yi = _mm256_load_pd(a.y + 4 * static_cast<std::ptrdiff_t>(i));
    const __m256d s0_i = _mm256_set1_pd(Alpha ? a.s0[i] : 0.0);
    RowSums row{_mm256_setzero_pd()};
    const long end = a.offset[i + 1];
    for (long k0 = a.offset[i]; k0 < end; k0 += 4) {
      load_group(a, cls, k0, end, yi, g);
      evaluate<Half, Plastic, Alpha, Energy, OneLaw>(a, g, s0_i, b);
      add<Half, Plastic, Alpha, Energy>(t, g, static_cast<int>(std::min<long>(4, end - k0)), b, row,
                                        sums);
    }
    write_row<Half, Alpha, Energy>(a, i, row, out, sums);
  }
  return sums;
}

template <bool H, bool P, bool A, bool E, class Index>
MF_TARGET_AVX2 MF_ALWAYS_INLINE Sums of_law(const Arrays& a, const Index* cls, int lo, int hi,
                                            const Output& out) {
  return a.law ? run_rows<H, P, A, E, true>(a, cls, lo, hi, out)
               : run_rows<H, P, A, E, false>(a, cls, lo, hi, out);
}

template <bool H, bool P, bool A, bool E>
MF_TARGET_AVX2 MF_ALWAYS_INLINE Sums of_index(const Arrays& a, int lo, int hi, const Output& out) {
  return a.cls.narrow ? of_law<H, P, A, E>(a, a.cls.narrow, lo, hi, out)
                      : of_law<H, P, A, E>(a, a.cls.wide, lo, hi, out);
}

using RowsFn = Sums (*)(const Arrays&, int, int, const Output&);

template <bool H, bool P, bool A, bool E>
MF_TARGET_AVX2 Sums rows_avx2(const Arrays& a, int lo, int hi, const Output& out) {
  return of_index<H, P, A, E>(a, lo, hi, out);
}

/// The same rows in AVX-512's encoding (the vector registers and the instructions are AVX2's).
template <bool H, bool P, bool A, bool E>
MF_TARGET_AVX512 Sums rows_avx512(const Arrays& a, int lo, int hi, const Output& out) {
  return of_index<H, P, A, E>(a, lo, hi, out);
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
