#pragma once
// The neighbour list of an SPH run, rebuilt only when a pair could be missing from it.
#include "meshfree/sph/hydro.hpp"

namespace mf::sph {

/// Rebuilds the neighbour list when a pair closer than 2 h could be missing from it.
void refresh_neighbours(Hydro& s);

} // namespace mf::sph
