#pragma once
// SPH spread over MPI ranks by spatial domain decomposition. Particles travel far in a blast, so
// ownership follows them, as LAMMPS's Comm::exchange and Comm::borders do: at the neighbour-list
// build that begins a step the owned particles are split again by their current positions and
// each one that changed slab migrates to its new owner with all its state; then every rank
// copies in, as remote ghosts, the other ranks' particles within the list's reach of its own
// (by bounding box), and refreshes them from their owners at every stage (distribution::Halo).
//
// The split: slabs along the body's longest axis, cut where the particle count reaches
// r N / ranks in a histogram of the positions over the body's extent (one reduction of the
// histogram). Slabs balance the count to within one bin and need no partitioner; beyond a few
// ranks recursive coordinate bisection (LAMMPS's comm_style tiled, Zoltan's RCB) keeps halos
// smaller, and slab_owners() is the one place that would change.
//
// Sums that do not depend on the split: each rank keeps its owned particles in increasing global
// id, and on more than one rank every neighbour row is sorted by (mirror planes, global id),
// which is the order a one-rank list has by construction. Every particle's sums then run in the
// same order whichever rank holds it, and two ranks reproduce one rank bit for bit in the
// particle fields; only sums over ranks (energies) are added in another order.
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/sph/hydro.hpp"
#include <vector>

namespace mf::sph {

/// Splits a body built whole on every rank (global id = index; its ghosts are dropped) over `ranks`:
/// each rank keeps its slab's particles and cuts its own part of each boundary condition out of
/// the whole body's, which it keeps (Conditions::keep_whole). On one rank it only records
/// `ranks`. Collective.
void distribute(Hydro& s, const distribution::Ranks& ranks);

/// Splits the owned particles again by their current positions; each that changed slab moves to
/// its new owner with its state, and the conditions are cut again. Drops every ghost.
/// Collective.
void migrate(Hydro& s);

/// After a rank's state was read back from a checkpoint (Hydro::for_each_state): cuts its part
/// of the conditions for its owned particles again and rebuilds the halo of its remote ghosts,
/// as they were. Collective; nothing on one rank.
void resume_distribution(Hydro& s);

/// Drops every ghost and copies in, as remote ghosts, the other ranks' particles that lie within
/// `reach` of this rank's owned particles' bounding box; builds the halo that refreshes them.
/// Collective.
void fetch_remote_ghosts(Hydro& s, double reach);

/// Refreshes every ghost: the remote ghosts' motion, density, energy, stress and history from
/// their owners (collective), then the mirror images from their sources.
void refresh_ghosts(Hydro& s);

/// Copies per-particle values (`per` a particle) of the owned particles into the remote ghosts'
/// slots of `a`. Collective.
void exchange_remote(const Hydro& s, std::vector<double>& a, int per);

/// Sorts every neighbour row by (mirror planes, global id): the order of the one-rank list.
void sort_rows_by_id(Hydro& s);

} // namespace mf::sph
