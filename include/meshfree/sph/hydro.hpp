#pragma once
// Smoothed-particle hydrodynamics of compressible media in 1, 2 or 3 dimensions ([Altafi 2018]
// chapter 3, after Monaghan 1992 and Liu & Liu 2003): continuity-equation density (eq. 3-41),
// the symmetric momentum and energy equations (eqs. 3-48 and 3-64) with Monaghan's artificial
// viscosity (alpha = beta = 1, phi = 0.1 h), smoothing lengths that follow the density, a
// midpoint predictor-corrector step under the CFL bound, equations of state per material,
// programmed burn of explosives (lighting time = distance / D_CJ) or a ZND front lit by its own
// shock, solid strength, symmetry planes (mirror particles), boundary conditions
// (sph/condition.hpp: loads, constant forces, transmitting boundaries), and the optional
// kernel-gradient correction and artificial stress. This header holds a run's data; the steps that
// act on it are declared in sph/state.hpp, sph/neighbours.hpp, sph/rates.hpp, sph/corrections.hpp,
// sph/step.hpp, sph/symmetry.hpp and sph/detonation.hpp.
#include "meshfree/distribution/halo.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/neighbors/pair_list.hpp"
#include "meshfree/particles/particle_set.hpp"
#include "meshfree/sph/condition.hpp"
#include "meshfree/sph/material.hpp"
#include "meshfree/sph/particle_fields.hpp"
#include "meshfree/sph/settings.hpp"
#include <string>
#include <vector>

namespace mf::sph {

/// A symmetry plane x_axis = at (Libersky & Petschek 1991; [Altafi 2018] type-II particles):
/// the particles within reach of the plane are mirrored across it, with the normal velocity and
/// the shear stresses on the plane reversed, so that the body behaves as half of a symmetric
/// whole: no normal motion through the plane and no shear on it.
struct SymmetryPlane {
  int axis = 0;
  double at = 0.0;
};

/// Forces on every free owned particle: body-level settings rather than conditions, summed
/// inside the pair sums' own loop over the particles and their work in one sum over them.
struct BodyForces {
  /// Body acceleration (gravity).
  double gravity[3] = {0.0, 0.0, 0.0};
  /// Mass-proportional viscous damping c [1/s]: a -= c v, while c > 0. It brings a body to rest
  /// under its loads (a settle phase before an event: dynamic relaxation, as LS-DYNA's
  /// *CONTROL_DYNAMIC_RELAXATION or Underwood 1983); c = 2 omega_1 damps the lowest mode omega_1
  /// critically. Switch it off (0) for the event.
  double damping = 0.0;
  bool any() const {
    return gravity[0] != 0.0 || gravity[1] != 0.0 || gravity[2] != 0.0 || damping > 0.0;
  }
};

/// The particles of each material, so that a material's laws are dispatched once for all of its
/// particles: members[start[m], start[m + 1]) in ascending order, of which
/// [start[m], owned_end[m]) are owned particles and the rest ghosts (mirror images).
struct MaterialGroups {
  std::vector<int> start, owned_end, members;
  int built_for = -1; // the particle count they were built for
  const int* of(std::size_t m) const { return members.data() + start[m]; }
  int count(std::size_t m) const { return start[m + 1] - start[m]; }
  int owned(std::size_t m) const { return owned_end[m] - start[m]; }
};

/// The neighbour lists of a rank's owned particles and what decides when they are built again
/// (sph/neighbours.hpp).
struct NeighbourState {
  neighbors::PairList pairs;      // rows of the owned particles: every partner, ascending
  neighbors::PairList half_pairs; // the same rows with partners j > i only (unless deterministic)
  std::vector<double> x_at_build, h_at_build; // positions and h when the list was built
  double build_radius = 0.0;
  int rebuilds = 0;
  double seconds = 0.0; // wall time in refresh_neighbours (checks and builds)
};

/// Owned particles whose density, and so smoothing length, was held at its bound
/// (ParticleFields::rho_lo, rho_hi): counted once a step, at its end, so over a run these are
/// particle-steps. at_max counts h held at its largest (the density at rho_lo).
struct SmoothingBoundHits {
  long at_min = 0, at_max = 0;
  SmoothingBoundHits& operator+=(const SmoothingBoundHits& o) {
    at_min += o.at_min, at_max += o.at_max;
    return *this;
  }
};

/// An SPH run's data: the particle layer (the set and SPH's fields), the materials, the solver's
/// settings, the neighbour state, the boundary conditions and body forces, and the distribution
/// over ranks.
struct Hydro {
  int dim = 3;
  particles::ParticleSet particles;
  ParticleFields fields;
  std::vector<Material> materials;
  Settings settings;
  NeighbourState neighbours;
  /// The loads and boundaries acting on this rank's particles (and, over several ranks, the whole
  /// body's, from which each rank cuts its own after particles migrate).
  Conditions conditions;
  BodyForces body;
  /// Work of the conditions, gravity and damping so far, so that kinetic + internal energy -
  /// external_work stays at its start.
  double external_work = 0.0;
  double damping_work = 0.0; // the damping's part of external_work (not positive)
  std::vector<SymmetryPlane> symmetry;
  /// The set's mirror image k (particle owned_count() + remote + k) mirrors particle
  /// ghost_source[k] (owned or a remote ghost) across the planes of ghost_planes[k] (bit q:
  /// symmetry[q]); images are rebuilt with the neighbour list and refreshed from their sources at
  /// every stage.
  std::vector<int> ghost_source;
  std::vector<int> ghost_planes;
  /// The MPI ranks the body is spread over (sph/decomposition.hpp). On one rank every particle
  /// of the body is owned and there is no remote ghost.
  distribution::Ranks ranks;
  long particles_total = 0; // over every rank
  /// Remote ghosts: copies of other ranks' particles within reach of this rank's, particles
  /// owned_count() .. owned_count() + remote - 1, refreshed through `halo`; the mirror images
  /// follow them.
  int remote = 0;
  std::vector<int> remote_owner; // the rank that owns each remote ghost
  distribution::Halo halo;
  long migrated = 0; // particles that moved to another rank so far
  SmoothingBoundHits bounded_h; // this rank's, over the steps so far
  MaterialGroups groups;
  bool any_solid() const;
  /// What changes as a run goes: this rank's particles (owned, remote ghosts and mirror images),
  /// fields, the neighbour lists, the material groups, the work of the loads, which rank owns
  /// each remote ghost and the conditions' own state (a checkpoint keeps them;
  /// sph::resume_distribution rebuilds the halo and cuts the rank's conditions from them).
  template <class Visit> void for_each_state(Visit&& visit) {
    particles.for_each_state(visit / "particles");
    fields.for_each_state(visit / "fields");
    NeighbourState& n = neighbours;
    visit("pairs.offset", n.pairs.offset), visit("pairs.partner", n.pairs.partner);
    visit("half_pairs.offset", n.half_pairs.offset);
    visit("half_pairs.partner", n.half_pairs.partner);
    visit("x_at_build", n.x_at_build), visit("h_at_build", n.h_at_build);
    visit("build_radius", n.build_radius), visit("rebuilds", n.rebuilds);
    visit("damping", body.damping), visit("external_work", external_work);
    visit("damping_work", damping_work), visit("ghost_source", ghost_source);
    visit("ghost_planes", ghost_planes), visit("groups.start", groups.start);
    visit("groups.owned_end", groups.owned_end), visit("groups.members", groups.members);
    visit("groups.built_for", groups.built_for);
    visit("remote", remote), visit("remote_owner", remote_owner), visit("migrated", migrated);
    visit("bounded_h.at_min", bounded_h.at_min), visit("bounded_h.at_max", bounded_h.at_max);
    conditions.for_each_state(visit / "conditions");
  }
};

/// Appends an owned particle at rest at x with reference volume and density, specific energy e
/// and smoothing length h; returns its index.
int add_particle(Hydro& s, const Vec3& x, double volume, double density, double e, double h,
                 int material, bool fixed = false);

/// Groups the particles by material when the particle count has changed since the last grouping
/// (or always, with `force`).
void group_materials(Hydro& s, bool force = false);

} // namespace mf::sph
