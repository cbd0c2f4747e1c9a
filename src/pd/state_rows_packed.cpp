// The packed rows of the LPS passes (state_rows.hpp; x86-64, AVX2): each row in groups of four
// bonds. A group's four partners' positions (four doubles a point) are loaded one bond to a
// register and transposed into columns; the lengths, extensions and (pass 2) the force factors
// t / r are computed four bonds at a time, the partners' dilatation, constants and (position-aware
// bodies) the classes' factors gathered into columns; then the bonds, in order, add to the row's
// sums, the partners' and the breaking tests as the scalar rows do. The file is compiled without
// contraction (no FMA) and without errno for sqrt (CMakeLists.txt), and every value is computed
// with the scalar rows' IEEE operations in their order, so that the two equal bit for bit.
#include "state_rows.hpp"
#if defined(__x86_64__) && defined(__GNUC__)
#include "packed_columns.hpp"
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace mf::pd::detail {
namespace {

using packed::transpose;

/// A group of four bonds of a row: the bonds k0 .. k0 + 3, or where the row ends first, its last
/// bond in the lanes past the end (computed, never summed); y_j - y_i a bond a register.
struct Group {
  long k[4];
  int j[4];
  const BondClass* c[4];
  std::uint32_t cls[4];
  __m256d d[4];
};

/// Lengths |xi|, distances r and extensions e = r - |xi| of a group, four lanes each.
struct Columns {
  __m256d length, r, e;
};

template <class Index>
MF_TARGET_AVX2 MF_ALWAYS_INLINE Columns load_group(const Family& f, const Index* cls, long k0,
                                                   long end, __m256d yi, Group& g) {
  for (int q = 0; q < 4; ++q) {
    const long k = std::min(k0 + q, end - 1);
    g.k[q] = k;
    g.j[q] = f.partner[k];
    g.cls[q] = cls[k];
    g.c[q] = &f.classes[g.cls[q]];
    g.d[q] = _mm256_sub_pd(_mm256_loadu_pd(f.y4 + 4 * static_cast<std::ptrdiff_t>(g.j[q])), yi);
  }
  __m256d x[4] = {g.d[0], g.d[1], g.d[2], g.d[3]};
  transpose(x); // dx, dy, dz, zero
  const __m256d r2 =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(x[0], x[0]), _mm256_mul_pd(x[1], x[1])),
                    _mm256_mul_pd(x[2], x[2]));
  Columns c;
  c.length = _mm256_set_pd(g.c[3]->length, g.c[2]->length, g.c[1]->length, g.c[0]->length);
  c.r = _mm256_sqrt_pd(r2);
  c.e = _mm256_sub_pd(c.r, c.length);
  return c;
}

/// Per lane: values[index[q]] for the group's partners or classes.
template <class Array, class Indices>
MF_TARGET_AVX2 MF_ALWAYS_INLINE __m256d gather(const Array* values, const Indices& index) {
  return _mm256_set_pd(values[index[3]], values[index[2]], values[index[1]], values[index[0]]);
}

template <class Index>
MF_TARGET_AVX2 void dilatation_rows(const Family& f, const Index* cls, int lo, int hi,
                                    double* theta, double* other, int base) {
  alignas(32) double q[4];
  for (int i = lo; i < hi; ++i) {
    const __m256d yi = _mm256_loadu_pd(f.y4 + 4 * static_cast<std::ptrdiff_t>(i));
    const long end = f.offset[i + 1];
    double sum = 0.0;
    for (long k0 = f.offset[i]; k0 < end; k0 += 4) {
      Group g;
      const Columns c = load_group(f, cls, k0, end, yi, g);
      // q = omega |xi| e, as (omega |xi|) e.
      _mm256_store_pd(q, _mm256_mul_pd(_mm256_mul_pd(gather(f.omega, g.cls), c.length), c.e));
      for (int l = 0; l < 4 && k0 + l < end; ++l) {
        if (!f.intact[g.k[l]]) continue;
        sum += q[l] * g.c[l]->weight;
        if (f.half && g.j[l] < f.owned) other[g.j[l] - base] += q[l] * g.c[l]->weight_partner;
      }
    }
    theta[i - (f.half ? base : 0)] += sum;
  }
}

/// A group's force factors g = t / r (zero where r is zero), the two ends' elastic deviatoric
/// extensions and influences, as force_rows computes them: t = omega ((iso_i [dil] + iso_j
/// [dil_p]) |xi| + b_i [dev] el_i + b_j [dev_p] el_j), el = e - theta |xi| / d.
struct Factors {
  alignas(32) double g[4], el_i[4], el_j[4], omega[4], stretch[4]; // stretch e / |xi|
};

template <bool kAware>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void force_factors(const Family& f, const StateTerms& t,
                                                   const Group& g, const Columns& c, __m256d iso_i,
                                                   __m256d b_i, __m256d t_i, Factors& out) {
  const __m256d omega = gather(f.omega, g.cls);
  __m256d p[4]; // the partners' theta / d, iso, b, 0: one load each, then columns
  for (int q = 0; q < 4; ++q)
    p[q] = _mm256_loadu_pd(t.partner + 4 * static_cast<std::ptrdiff_t>(g.j[q]));
  transpose(p);
  const __m256d t_j = p[0], iso_j = p[1], b_j = p[2];
  const __m256d el_i = _mm256_sub_pd(c.e, _mm256_mul_pd(t_i, c.length));
  const __m256d el_j = _mm256_sub_pd(c.e, _mm256_mul_pd(t_j, c.length));
  __m256d sum;
  if constexpr (kAware) {
    const BondClass *c0 = g.c[0], *c1 = g.c[1], *c2 = g.c[2], *c3 = g.c[3];
    const __m256d di = _mm256_set_pd(c3->dil, c2->dil, c1->dil, c0->dil);
    const __m256d dj =
        _mm256_set_pd(c3->dil_partner, c2->dil_partner, c1->dil_partner, c0->dil_partner);
    const __m256d vi = _mm256_set_pd(c3->dev, c2->dev, c1->dev, c0->dev);
    const __m256d vj =
        _mm256_set_pd(c3->dev_partner, c2->dev_partner, c1->dev_partner, c0->dev_partner);
    sum =
        _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(iso_i, di), _mm256_mul_pd(iso_j, dj)), c.length);
    sum = _mm256_add_pd(sum, _mm256_mul_pd(_mm256_mul_pd(b_i, vi), el_i));
    sum = _mm256_add_pd(sum, _mm256_mul_pd(_mm256_mul_pd(b_j, vj), el_j));
  } else {
    sum = _mm256_mul_pd(_mm256_add_pd(iso_i, iso_j), c.length);
    sum = _mm256_add_pd(sum, _mm256_mul_pd(b_i, el_i));
    sum = _mm256_add_pd(sum, _mm256_mul_pd(b_j, el_j));
  }
  const __m256d T = _mm256_mul_pd(omega, sum);
  const __m256d positive = _mm256_cmp_pd(c.r, _mm256_setzero_pd(), _CMP_GT_OQ);
  _mm256_store_pd(out.g, _mm256_and_pd(_mm256_div_pd(T, c.r), positive));
  _mm256_store_pd(out.el_i, el_i);
  _mm256_store_pd(out.el_j, el_j);
  _mm256_store_pd(out.omega, omega);
  _mm256_store_pd(out.stretch, _mm256_div_pd(c.e, c.length));
}

/// A row's running sums.
struct RowSums {
  __m256d f;
  double w = 0.0, s0 = kNone;
  long broken = 0;
};

/// Bond l of a group in its turn, as force_rows adds it: its force to the row's, its reaction,
/// energy and s0 candidate to an owned partner's (half layout), then its breaking test.
template <bool kAware>
MF_TARGET_AVX2 MF_ALWAYS_INLINE void add_bond(const Family& f, const StateTerms& t,
                                              const PassOut& out, const Group& g, const Factors& b,
                                              int l, double bi, double s0_i, RowSums& row) {
  const long k = g.k[l];
  const int j = g.j[l];
  const BondClass& c = *g.c[l];
  const double gi = b.g[l] * c.weight;
  row.f = _mm256_add_pd(row.f, _mm256_mul_pd(_mm256_set1_pd(gi), g.d[l]));
  const bool j_row = f.half && j < f.owned;
  const std::ptrdiff_t jb = j - out.base;
  alignas(32) double d[4];
  _mm256_store_pd(d, g.d[l]);
  if (j_row) {
    const double gj = b.g[l] * c.weight_partner;
    out.f[3 * jb] -= gj * d[0], out.f[3 * jb + 1] -= gj * d[1], out.f[3 * jb + 2] -= gj * d[2];
  }
  if (t.energy) {
    const double omega = b.omega[l], ei = b.el_i[l], ej = b.el_j[l];
    row.w += 0.5 * bi * (kAware ? c.dev * omega : omega) * ei * ei * c.weight;
    if (j_row)
      out.w[jb] +=
          0.5 * t.b[j] * (kAware ? c.dev_partner * omega : omega) * ej * ej * c.weight_partner;
  }
  const double stretch = b.stretch[l];
  if (t.s0) {
    const double candidate = c.s00 - c.alpha * stretch;
    row.s0 = std::max(row.s0, candidate);
    if (j_row) out.s0n[jb] = std::max(out.s0n[jb], candidate);
  }
  if (t.breaking && stretch > critical(c, t.s0, s0_i, j)) {
    f.intact[k] = 0;
    row.broken += j_row ? 2 : 1;
  }
}

template <bool kAware, class Index>
MF_TARGET_AVX2 long force_rows(const Family& f, const StateTerms& t, const Index* cls, int lo,
                               int hi, const PassOut& out) {
  long broken = 0;
  for (int i = lo; i < hi; ++i) {
    const __m256d yi = _mm256_loadu_pd(f.y4 + 4 * static_cast<std::ptrdiff_t>(i));
    const double bi = t.b[i], s0_i = t.s0 ? t.s0[i] : 0.0;
    const __m256d iso_i = _mm256_set1_pd(t.iso[i]), b_i = _mm256_set1_pd(bi);
    const __m256d t_i = _mm256_set1_pd(t.partner[4 * static_cast<std::ptrdiff_t>(i)]);
    const long end = f.offset[i + 1];
    RowSums row;
    row.f = _mm256_setzero_pd();
    // Two groups' factors before their sums, so that the second's square roots and divisions
    // overlap the first's sums.
    for (long k0 = f.offset[i]; k0 < end; k0 += 8) {
      Group g[2];
      Factors b[2];
      const int groups = k0 + 4 < end ? 2 : 1;
      for (int h = 0; h < groups; ++h) {
        const Columns c = load_group(f, cls, k0 + 4 * h, end, yi, g[h]);
        force_factors<kAware>(f, t, g[h], c, iso_i, b_i, t_i, b[h]);
      }
      for (int h = 0; h < groups; ++h)
        for (int l = 0; l < 4 && k0 + 4 * h + l < end; ++l)
          if (f.intact[g[h].k[l]]) add_bond<kAware>(f, t, out, g[h], b[h], l, bi, s0_i, row);
    }
    alignas(32) double fi[4];
    _mm256_store_pd(fi, row.f);
    const std::ptrdiff_t ib = i - out.base;
    out.f[3 * ib] += fi[0], out.f[3 * ib + 1] += fi[1], out.f[3 * ib + 2] += fi[2];
    if (t.energy) out.w[ib] += row.w + 0.5 * t.kappa[i] * t.theta[i] * t.theta[i];
    if (t.s0) out.s0n[ib] = std::max(out.s0n[ib], row.s0);
    broken += row.broken;
  }
  return broken;
}

} // namespace

void packed_dilatation_rows(const Family& f, int lo, int hi, double* theta, double* other,
                            int base) {
  if (f.cls.narrow)
    dilatation_rows(f, f.cls.narrow, lo, hi, theta, other, base);
  else
    dilatation_rows(f, f.cls.wide, lo, hi, theta, other, base);
}

long packed_force_rows(const Family& f, const StateTerms& t, int lo, int hi, const PassOut& out) {
  if (f.aware)
    return f.cls.narrow ? force_rows<true>(f, t, f.cls.narrow, lo, hi, out)
                        : force_rows<true>(f, t, f.cls.wide, lo, hi, out);
  return f.cls.narrow ? force_rows<false>(f, t, f.cls.narrow, lo, hi, out)
                      : force_rows<false>(f, t, f.cls.wide, lo, hi, out);
}

} // namespace mf::pd::detail
#endif
