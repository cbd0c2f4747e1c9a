#pragma once
// The instruction sets the particle loops are compiled for, which of them this processor runs,
// and the one the loops use, chosen once for the program: the peridynamic bond rows
// (pd/bond_rows.hpp) and the SPH pair rows (sph/live_pairs.hpp, sph/pair_sums.hpp) give the same
// numbers bit for bit under every target, so a run's results do not depend on the processor.
#include <vector>

namespace mf {

/// x86-64's baseline (SSE2, two lanes), AVX2 (four) and AVX-512 (eight; x86-64-v4). Other
/// processors have the baseline only.
enum class SimdTarget { Baseline, Avx2, Avx512 };

const char* simd_target_name(SimdTarget t);
/// The targets this processor runs, narrowest first (the baseline always).
std::vector<SimdTarget> simd_targets();
/// The target the loops use unless set: AVX2 where the processor has it, else the baseline.
SimdTarget preferred_simd_target();
/// The target the loops use.
SimdTarget simd_target();
/// Makes the loops use `t` (one this processor runs; for comparisons and timings).
void set_simd_target(SimdTarget t);

} // namespace mf
