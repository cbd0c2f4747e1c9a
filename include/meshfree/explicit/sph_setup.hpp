#pragma once
// An SPH body built from a problem file (analysis: sph): particles of the regions (lattices less
// holes, rings), surface blasts per particle, constant tractions, gravity, transmitting
// boundaries, symmetry planes and the lighting times of a detonation.
#include "meshfree/spec/sph_spec.hpp"
#include "meshfree/sph/hydro.hpp"

namespace mf::explicit_dynamics {

/// The particles of a spec, in the initial state of its regions, lit if the spec detonates.
sph::Hydro build_sph(const spec::SphSpec& s);

} // namespace mf::explicit_dynamics
