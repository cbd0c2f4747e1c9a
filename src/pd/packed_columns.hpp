#pragma once
// What the packed rows (bond_rows_packed.cpp, state_rows_packed.cpp; x86-64) share: their
// targets and the transpose of four bonds' registers into columns.
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

#define MF_TARGET_AVX2 __attribute__((target("avx2")))
#define MF_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512bw,avx512dq,avx512cd")))
#define MF_ALWAYS_INLINE __attribute__((always_inline)) inline

namespace mf::pd::packed {

/// Four rows of four doubles as four columns.
MF_TARGET_AVX2 MF_ALWAYS_INLINE void transpose(__m256d r[4]) {
  const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
  const __m256d t2 = _mm256_unpacklo_pd(r[2], r[3]), t3 = _mm256_unpackhi_pd(r[2], r[3]);
  r[0] = _mm256_permute2f128_pd(t0, t2, 0x20), r[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  r[2] = _mm256_permute2f128_pd(t0, t2, 0x31), r[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

} // namespace mf::pd::packed
#endif
