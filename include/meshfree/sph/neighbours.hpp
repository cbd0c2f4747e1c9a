#pragma once
// The neighbour list of an SPH run, rebuilt only when a pair could be missing from it.
#include "meshfree/sph/hydro.hpp"

namespace mf::sph {

/// Rebuilds the neighbour list when a pair closer than 2 h could be missing from it (a Verlet
/// list: a particle moved or grew its h by more than skin h since the last build). The list
/// holds the pairs within (h_i + h_j)(1 + skin), found per class of h
/// (neighbors::pairs_within_reach); rows of owned particles, partners owned or ghosts, each row
/// in increasing partner index (on more than one rank: in increasing (mirror planes, global
/// id)); ghosts' rows are empty. On more than one rank a build fetches the remote ghosts first,
/// and with `may_migrate` (the build that begins a step) re-splits the particles over the ranks
/// before that (sph/decomposition.hpp). Collective.
void refresh_neighbours(Hydro& s, bool may_migrate = false);

} // namespace mf::sph
