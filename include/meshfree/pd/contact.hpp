#pragma once
// Rigid impactors in contact with a peridynamic body, two laws:
//  - kinematic (Madenci & Oterkus 2014, sec. 10.3): a particle found inside after the drift is
//    put back on the surface (a sphere radially, a flat nose along the impact direction onto the
//    leading face), its velocity becomes the one that moved it there, and the momentum it gained
//    is taken from the impactor. Each such exchange is a perfectly plastic collision of the
//    particle with the impactor: the kinetic energy it destroys is counted as dissipated;
//  - penalty, the force law of LAMMPS `fix indent` (src/fix_indent.cpp, FixIndent::post_force):
//    a particle at depth d = R - r inside a sphere gets the force per unit volume K d^2 along the
//    outward normal (with atom_style peri LAMMPS's per-atom force is a force density, fix nve
//    divides it by the density rmass), potential K d^3 / 3 per unit volume (the fix's energy,
//    indenter[0] -= k3 dr^3). A flat nose uses the `plane` variant on its leading face: depth d
//    behind the face inside the block, force K d^2 along the impact direction.
// An impactor is free (its mass moves under the reaction, velocity Verlet for a penalty contact),
// fixed (a support), or prescribed (moves at its constant velocity whatever the reaction, as
// LAMMPS's variable-driven indenter; the work its drive does is counted).
#include "meshfree/core/types.hpp"
#include "meshfree/distribution/ranks.hpp"
#include "meshfree/particles/particle_set.hpp"
#include <string>
#include <vector>

namespace mf::pd {

struct Impactor {
  enum class Shape { Sphere, Flat };
  enum class Law { Kinematic, Penalty };
  std::string name;
  Shape shape = Shape::Sphere;
  Law law = Law::Kinematic;
  double stiffness = 0.0;                   // penalty K: force per volume per length^2
  double radius = 0.0;                      // sphere
  Eigen::Vector3d half_size{0.0, 0.0, 0.0}; // flat: half extents of the block
  Eigen::Vector3d direction{0.0, -1.0,
                            0.0}; // flat: unit impact direction (the leading face's normal)
  double mass = 0.0;
  bool fixed = false;      // a support: it does not move, whatever the contact pushes
  bool prescribed = false; // moves at `velocity` whatever the contact pushes
  Eigen::Vector3d position{0.0, 0.0, 0.0}, velocity{0.0, 0.0, 0.0};
  Eigen::Vector3d contact_force{0.0, 0.0, 0.0}; // on the impactor, last step
  double contact_energy = 0.0; // penalty potential sum_i V_i K d_i^3 / 3 of the current state
  double work = 0.0;           // work of the drive of a prescribed impactor on the body, so far
  double dissipated = 0.0;     // kinetic energy destroyed by kinematic contact, so far

  bool free() const { return !fixed && !prescribed; }
  /// What changes as a run goes: the motion, the last contact force and the energy accounts.
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("position", position), visit("velocity", velocity);
    visit("contact_force", contact_force), visit("contact_energy", contact_energy);
    visit("work", work), visit("dissipated", dissipated);
  }
  double kinetic_energy() const { return free() ? 0.5 * mass * velocity.squaredNorm() : 0.0; }
};

/// Kinematic contact of one impactor with the particles at their current positions (after the
/// drift, velocities at the half step): moves and speeds up the particles inside, updates the
/// impactor's velocity (free), contact force, drive work (prescribed) and dissipated energy.
/// Acts on the owned particles; the impulse is summed over `ranks` (collective).
void kinematic_contact(particles::ParticleSet& p, Impactor& imp, double dt,
                       const distribution::Ranks& ranks = {});

/// Penalty contact of one impactor at particle positions y (3 per particle): adds the force
/// densities to `force` and sets the impactor's contact force (-sum_i V_i f_i) and energy. Acts
/// on the owned particles; force and energy are summed over `ranks` (collective).
void penalty_contact(const particles::ParticleSet& p, const std::vector<double>& y, Impactor& imp,
                     std::vector<double>& force, const distribution::Ranks& ranks = {});

/// The penalty stiffness used when none is given: K = C / (4 dx), C the largest bond stiffness
/// sum_j c_ij w_ij / |xi_ij| of a particle (the sum of Silling & Askari's stable-step bound, C =
/// 2 rho / dt_c^2). At a depth of one spacing the contact's tangent stiffness per unit volume 2 K
/// dx is then C / 2, so the stable step with the contact, dt_c / sqrt(1.5) = 0.816 dt_c, stays
/// above the default step (safety 0.8) while particles are less than a spacing deep.
double derived_penalty_stiffness(double density, double stable_dt, double spacing);

} // namespace mf::pd
