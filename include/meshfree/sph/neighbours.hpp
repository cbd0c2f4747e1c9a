#pragma once
// The neighbour list of an SPH run, rebuilt only when a pair could be missing from it.
#include "meshfree/sph/hydro.hpp"

namespace mf::sph {

/// Rebuilds the neighbour list when a pair closer than 2 h could be missing from it (a Verlet
/// list: a particle moved or grew its h by more than skin h since the last build). The list
/// holds the pairs within (h_i + h_j)(1 + skin), found per class of h
/// (neighbors::pairs_within_reach); rows of owned particles, partners owned or ghosts, each row
/// in increasing partner index; ghosts' rows are empty.
void refresh_neighbours(Hydro& s);

} // namespace mf::sph
