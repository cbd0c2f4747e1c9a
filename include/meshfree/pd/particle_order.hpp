#pragma once
// Particles in the order of a space-filling curve through their reference positions, so that
// the partners of a particle's bonds lie close to it in memory (the reads of the bond loop stay
// in cache).
#include "meshfree/particles/particle_set.hpp"
#include <cstdint>
#include <vector>

namespace mf::pd {

/// Morton (Z-order) key of the reference position x on a grid of cell `cell` from `lo`: the bits
/// of the three cell indices (21 each) interleaved (Morton 1966).
std::uint64_t morton_key(const double* x, const double* lo, double cell);

/// Reorders the particles (all of them owned, no ghost) by the Morton key of their reference
/// positions on a grid of the spacing, ties by the old index, and gives them global ids 0, 1, ...
/// in the new order. Returns the permutation: new particle k was old particle order[k].
std::vector<int> order_along_curve(particles::ParticleSet& p, double spacing);

} // namespace mf::pd
