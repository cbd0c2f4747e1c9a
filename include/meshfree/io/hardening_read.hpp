#pragma once
#include "meshfree/io/key_reader.hpp"
#include "meshfree/materials/j2_plasticity.hpp"

namespace mf::io {

/// The J2 yield stress and isotropic hardening law of a map with `yield_stress` and `hardening`
/// (perfect | {type: linear|voce|swift|table, ...}); sets j.sigma0 (Swift and table laws define
/// it themselves). Used by material.plasticity and by SPH strength.
void read_hardening(KeyReader& p, materials::J2Parameters& j);

} // namespace mf::io
