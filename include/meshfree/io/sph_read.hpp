#pragma once
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/sph_spec.hpp"

namespace mf::io {

/// Reads the SPH sections of a problem file (analysis: sph).
SphSpec parse_sph(KeyReader& r);

} // namespace mf::io
