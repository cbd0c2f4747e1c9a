// The live-pair selection of sph/live_pairs.hpp: the scalar rows, and the AVX2 rows (x86-64),
// which take four pairs at a time with the scalar rows' IEEE operations in their order, and
// their kernel slopes, one loop compiled for each (the file is compiled without contraction into
// fused multiply-adds and without errno for sqrt, CMakeLists.txt), so that both keep the same
// pairs with the same values bit for bit.
#include "meshfree/sph/live_pairs.hpp"
#include <cmath>
#if defined(__x86_64__) && defined(__GNUC__)
#include <array>
#include <immintrin.h>
#define MF_SPH_X86 1
#else
#define MF_SPH_X86 0
#endif

namespace mf::sph {

void LivePairs::reserve(std::size_t n) {
  if (j.size() >= n) return;
  j.resize(n);
  for (std::vector<double>* a : {&r2, &h, &g, &m, &vol, &c, &rho, &q, &vg, &w, &push}) a->resize(n);
  for (int d = 0; d < 3; ++d)
    for (std::vector<double>* a : {&x[d], &v[d], &gv[d], &gi[d], &gj[d], &f[d]}) a->resize(n);
  for (std::vector<double>& a : T) a.resize(n);
}

namespace {

/// Pairs [k, end) of a row whose own particle is at xi with h_i = hi, written from slot `count`
/// on; returns the new count. Without a branch: every pair is written at the next free slot,
/// which advances only for an interacting pair (about half of the list is the skin, in no
/// predictable pattern).
template <int Dim>
int select_scalar(const int* partner, long k, long end, const double* xh, const double xi[3],
                  double hi, LivePairs& live, int count) {
  for (; k < end; ++k) {
    const int j = partner[k];
    const double* xj = &xh[4 * static_cast<std::size_t>(j)];
    const double d0 = xi[0] - xj[0];
    const double d1 = Dim > 1 ? xi[1] - xj[1] : 0.0;
    const double d2 = Dim > 2 ? xi[2] - xj[2] : 0.0;
    double r2 = d0 * d0;
    if constexpr (Dim > 1) r2 += d1 * d1;
    if constexpr (Dim > 2) r2 += d2 * d2;
    const double hij = 0.5 * (hi + xj[3]);
    live.j[count] = j;
    live.x[0][count] = d0;
    if constexpr (Dim > 1) live.x[1][count] = d1;
    if constexpr (Dim > 2) live.x[2][count] = d2;
    live.r2[count] = r2, live.h[count] = hij;
    count += !(r2 >= 4.0 * hij * hij) & (r2 != 0.0);
  }
  return count;
}

/// grad W / r for pairs [0, count), with the kernel's dimension fixed at compile time so that the
/// loop has no branch the compiler cannot turn into a select: packed, two lanes on the baseline,
/// four where it is inlined into the AVX2 rows.
template <int Dim>
__attribute__((always_inline)) inline void slopes(kernels::SphKernel kernel, LivePairs& live,
                                                  int count) {
  const double *r2 = live.r2.data(), *h = live.h.data();
  double* g = live.g.data();
  if (kernel == kernels::SphKernel::CubicSpline)
    for (int t = 0; t < count; ++t)
      g[t] = kernels::cubic_spline_slope_over_r(Dim, std::sqrt(r2[t]), h[t]);
  else
    for (int t = 0; t < count; ++t)
      g[t] = kernels::wendland_c2_slope_over_r(Dim, std::sqrt(r2[t]), h[t]);
}

#if MF_SPH_X86

/// For each 4-bit mask of kept lanes, the 32-bit lane indices that move the kept 64-bit lanes to
/// the front in order (pairs of indices, `wide`) and the kept 32-bit lanes (`narrow`).
struct Compaction {
  alignas(32) std::array<std::array<int, 8>, 16> wide{}, narrow{};
  constexpr Compaction() {
    for (int m = 0; m < 16; ++m) {
      int out = 0;
      for (int lane = 0; lane < 4; ++lane)
        if (m & (1 << lane)) {
          wide[m][2 * out] = 2 * lane, wide[m][2 * out + 1] = 2 * lane + 1;
          narrow[m][out] = lane;
          ++out;
        }
    }
  }
};
constexpr Compaction kCompaction;

__attribute__((target("avx2"))) inline void store_kept(double* at, __m256d v, __m256i wide) {
  _mm256_storeu_pd(at,
                   _mm256_castsi256_pd(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(v), wide)));
}

/// The AVX2 rows: four partners' (x, y, z, h) loaded as four rows and transposed into columns,
/// the four pairs' differences, r^2, h_ij and test as the scalar rows compute them, and the kept
/// lanes stored from slot `count` on. Writes up to three slots past the kept pairs, within the
/// row's length since a block of four starts at most at its slot.
template <int Dim>
__attribute__((target("avx2"))) int select_avx2(const int* partner, long begin, long end,
                                                const double* xh, const double xi[3], double hi,
                                                kernels::SphKernel kernel, LivePairs& live) {
  const __m256d x0 = _mm256_set1_pd(xi[0]), x1 = _mm256_set1_pd(xi[1]), x2 = _mm256_set1_pd(xi[2]),
                h_i = _mm256_set1_pd(hi);
  const __m256d half = _mm256_set1_pd(0.5), four = _mm256_set1_pd(4.0), zero = _mm256_setzero_pd();
  int count = 0;
  long k = begin;
  for (; k + 4 <= end; k += 4) {
    const __m256d p0 = _mm256_loadu_pd(&xh[4 * static_cast<std::size_t>(partner[k])]);
    const __m256d p1 = _mm256_loadu_pd(&xh[4 * static_cast<std::size_t>(partner[k + 1])]);
    const __m256d p2 = _mm256_loadu_pd(&xh[4 * static_cast<std::size_t>(partner[k + 2])]);
    const __m256d p3 = _mm256_loadu_pd(&xh[4 * static_cast<std::size_t>(partner[k + 3])]);
    const __m256d t0 = _mm256_unpacklo_pd(p0, p1), t1 = _mm256_unpackhi_pd(p0, p1);
    const __m256d t2 = _mm256_unpacklo_pd(p2, p3), t3 = _mm256_unpackhi_pd(p2, p3);
    const __m256d d0 = _mm256_sub_pd(x0, _mm256_permute2f128_pd(t0, t2, 0x20));
    const __m256d d1 = _mm256_sub_pd(x1, _mm256_permute2f128_pd(t1, t3, 0x20));
    const __m256d d2 = _mm256_sub_pd(x2, _mm256_permute2f128_pd(t0, t2, 0x31));
    const __m256d hj = _mm256_permute2f128_pd(t1, t3, 0x31);
    __m256d r2 = _mm256_mul_pd(d0, d0);
    if constexpr (Dim > 1) r2 = _mm256_add_pd(r2, _mm256_mul_pd(d1, d1));
    if constexpr (Dim > 2) r2 = _mm256_add_pd(r2, _mm256_mul_pd(d2, d2));
    const __m256d hij = _mm256_mul_pd(half, _mm256_add_pd(h_i, hj));
    const __m256d reach = _mm256_mul_pd(_mm256_mul_pd(four, hij), hij);
    const __m256d keep =
        _mm256_and_pd(_mm256_cmp_pd(r2, reach, _CMP_NGE_UQ), _mm256_cmp_pd(r2, zero, _CMP_NEQ_UQ));
    const int mask = _mm256_movemask_pd(keep);
    const __m256i wide = _mm256_load_si256(
        reinterpret_cast<const __m256i*>(kCompaction.wide[static_cast<std::size_t>(mask)].data()));
    const __m256i narrow = _mm256_load_si256(reinterpret_cast<const __m256i*>(
        kCompaction.narrow[static_cast<std::size_t>(mask)].data()));
    const __m128i js = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&partner[k]));
    _mm_storeu_si128(
        reinterpret_cast<__m128i*>(&live.j[count]),
        _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_castsi128_si256(js), narrow)));
    store_kept(&live.x[0][count], d0, wide);
    if constexpr (Dim > 1) store_kept(&live.x[1][count], d1, wide);
    if constexpr (Dim > 2) store_kept(&live.x[2][count], d2, wide);
    store_kept(&live.r2[count], r2, wide);
    store_kept(&live.h[count], hij, wide);
    count += __builtin_popcount(static_cast<unsigned>(mask));
  }
  // The upper halves of the vector registers cleared before the baseline code runs again, said
  // here rather than left to the compiler: GCC 12 once called the scalar tail without it, and
  // with them left dirty every later SSE instruction of the process waited on them (the SPH
  // tunnel's steps took twice as long).
  _mm256_zeroupper();
  count = select_scalar<Dim>(partner, k, end, xh, xi, hi, live, count);
  slopes<Dim>(kernel, live, count);
  _mm256_zeroupper();
  return count;
}

#endif

template <int Dim>
int select_dim(const neighbors::PairList& list, const double* xh, int i, kernels::SphKernel kernel,
               LivePairs& live, SimdTarget target) {
  const long begin = list.offset[i], end = list.offset[i + 1];
  live.reserve(static_cast<std::size_t>(end - begin));
  const double xi[3] = {xh[4 * i], xh[4 * i + 1], xh[4 * i + 2]}, hi = xh[4 * i + 3];
#if MF_SPH_X86
  // Short rows (a 1D body's) cost more packed than scalar: Sod's tube ran 14% slower.
  if (target != SimdTarget::Baseline && end - begin >= 8)
    return select_avx2<Dim>(list.partner.data(), begin, end, xh, xi, hi, kernel, live);
#endif
  const int count = select_scalar<Dim>(list.partner.data(), begin, end, xh, xi, hi, live, 0);
  slopes<Dim>(kernel, live, count);
  return count;
}

} // namespace

int select_live_pairs(int dim, const neighbors::PairList& list, const double* xh, int i,
                      kernels::SphKernel kernel, LivePairs& live, SimdTarget target) {
  switch (dim) {
  case 1:
    return select_dim<1>(list, xh, i, kernel, live, target);
  case 2:
    return select_dim<2>(list, xh, i, kernel, live, target);
  default:
    return select_dim<3>(list, xh, i, kernel, live, target);
  }
}

} // namespace mf::sph
