#include "meshfree/core/simd_target.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <atomic>

namespace mf {

const char* simd_target_name(SimdTarget t) {
  switch (t) {
  case SimdTarget::Avx2:
    return "avx2";
  case SimdTarget::Avx512:
    return "avx512";
  default:
    return "baseline";
  }
}

std::vector<SimdTarget> simd_targets() {
  std::vector<SimdTarget> t{SimdTarget::Baseline};
#if defined(__x86_64__) && defined(__GNUC__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) t.push_back(SimdTarget::Avx2);
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd"))
    t.push_back(SimdTarget::Avx512);
#endif
  return t;
}

namespace {

/// AVX2 where the processor has it, else the baseline: the AVX-512 bond rows store their
/// columns four lanes at a time and read them eight at a time, and are no faster (README,
/// peridynamic bond loop); the SPH selection has no AVX-512 form.
SimdTarget preferred() {
  const std::vector<SimdTarget> t = simd_targets();
  return std::find(t.begin(), t.end(), SimdTarget::Avx2) != t.end() ? SimdTarget::Avx2
                                                                    : SimdTarget::Baseline;
}

std::atomic<int>& chosen() {
  static std::atomic<int> t{static_cast<int>(preferred())};
  return t;
}

} // namespace

SimdTarget preferred_simd_target() {
  return preferred();
}

SimdTarget simd_target() {
  return static_cast<SimdTarget>(chosen().load());
}

void set_simd_target(SimdTarget t) {
  const std::vector<SimdTarget> ok = simd_targets();
  MF_REQUIRE(std::find(ok.begin(), ok.end(), t) != ok.end(), "this processor has no ",
             simd_target_name(t), " instructions");
  chosen() = static_cast<int>(t);
}

} // namespace mf
