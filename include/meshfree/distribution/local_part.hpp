#pragma once
// One rank's part of a body whose particles do not change ownership (peridynamics: bonds join
// reference positions, so the halo is fixed at the start): the rank's block of ids as owned
// particles, then every other particle within `reach` of one of them as a ghost, grouped by
// owner; and the halo that keeps the ghosts' copies up to date.
#include "meshfree/distribution/halo.hpp"
#include "meshfree/particles/particle_set.hpp"
#include <vector>

namespace mf::distribution {

struct LocalPart {
  particles::ParticleSet particles; // owned (in id order), then ghosts (by owner, then id)
  std::vector<int> local_of;        // global index -> local index, -1 where not held
  Halo halo;
  long first = 0; // the first owned id: owned particle i has id first + i
};

/// The part of `whole` (every particle of the body, global index = id, on every rank) that rank
/// `ranks.rank` holds. The ghosts carry their reference data and current motion. Collective.
LocalPart local_part(const particles::ParticleSet& whole, const Ranks& ranks, double reach);

/// The entries of `items` (one per index of `group`, a list of global indices) whose particle
/// this rank owns, with the group turned into local indices: for per-particle data that is built
/// on the whole body (a load's particles and their own values) before it is split.
template <class T>
void keep_owned(std::vector<int>& group, std::vector<T>& items, const LocalPart& part) {
  std::size_t kept = 0;
  const int owned = part.particles.owned_count();
  for (std::size_t k = 0; k < group.size(); ++k) {
    const int i = part.local_of[group[k]];
    if (i < 0 || i >= owned) continue;
    if (!items.empty()) items[kept] = items[k];
    group[kept++] = i;
  }
  group.resize(kept);
  if (!items.empty()) items.resize(kept);
}

/// keep_owned for a group with no per-particle data.
void keep_owned(std::vector<int>& group, const LocalPart& part);

} // namespace mf::distribution
