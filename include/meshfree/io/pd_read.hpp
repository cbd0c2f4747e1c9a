#pragma once
// Reading the peridynamics part of a problem file into a PdSpec.
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/pd_spec.hpp"
#include <string>

namespace mf::io {

/// Reads model, geometry (3D box; a 2D body's geometry is read by the caller), materials,
/// interfaces, discretisation, regions, notches, cracks, initial_velocity, functions, boundary,
/// impactors, time and output. `base_dir` resolves relative file names.
PdSpec parse_pd(KeyReader& r, const std::string& base_dir);

} // namespace mf::io
