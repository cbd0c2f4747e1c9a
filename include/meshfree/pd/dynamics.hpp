#pragma once
// Explicit dynamics of a peridynamic body: velocity Verlet (the half kick, drift, force, half
// kick of LAMMPS's fix nve; paper 000 eq. 9), body forces and tractions turned into body forces,
// prescribed displacement and velocity components, rigid impactors (pd/contact.hpp) and the
// optional short-range contact of particles (pd/short_range.hpp).
#include "meshfree/loads/blast.hpp"
#include "meshfree/loads/time_function.hpp"
#include "meshfree/pd/contact.hpp"
#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/fracture_energy.hpp"
#include "meshfree/pd/model.hpp"
#include "meshfree/pd/short_range.hpp"
#include <string>
#include <vector>

namespace mf::pd {

/// Prescribed components of displacement (or velocity) on a set of particles: value times the
/// time function (`function` < 0: constant 1). A displacement constraint may instead hold each
/// particle at its own value: when `held` is not empty, the fixed components of particles[k] are
/// held[k] times the time function (constant when there is none), e.g. a displacement field
/// taken over from an earlier analysis.
struct Constraint {
  std::string name;
  std::vector<int> particles;
  bool velocity = false;
  bool fixed[3] = {false, false, false};
  double value[3] = {0.0, 0.0, 0.0};
  int function = -1;
  std::vector<Eigen::Vector3d> held; // empty, or one per particle (displacement constraints only)

  /// The prescribed value of component d of the k-th particle, before the time function.
  double target(std::size_t k, int d) const { return held.empty() ? value[d] : held[k](d); }
};

/// A force per unit volume on a set of particles, times a time function. A traction t on a face
/// of area A becomes b = t A / (volume of the loaded layer of particles). A blast load gives each
/// particle its own pressure history (`pulses`, one per particle, in Pa) and `density` is the
/// force per volume of a unit pressure. Forces that differ from particle to particle (those of
/// an earlier analysis' boundary, say) go in `densities`, one per particle, instead of `density`.
struct BodyLoad {
  std::string name;
  std::vector<int> particles;
  Eigen::Vector3d density{0.0, 0.0, 0.0};
  int function = -1;
  std::vector<loads::Friedlander> pulses;
  std::vector<Eigen::Vector3d> densities; // empty, or one per particle

  /// Component d of the force per volume of the k-th particle, before the factors.
  double density_of(std::size_t k, int d) const {
    return densities.empty() ? density(d) : densities[k](d);
  }
};

/// The conditions of a peridynamic body: two closed lists of plain data rather than SPH's objects
/// with hooks (sph/condition.hpp), because the static solvers (pd/relaxation.hpp) and a staged
/// run's transfer read them as data too (a load vector at one instant, the held components), and
/// the particles they name never change rank, so no condition is cut again after a step. Their
/// hooks in the step are the members below, with the names SPH's conditions use where they do
/// the same: add_forces (post_force), power (the work), impose (kinematic components).
struct Loading {
  std::vector<loads::TimeFunction> functions;
  std::vector<Constraint> constraints;
  std::vector<BodyLoad> loads;
  double factor(int function, double t) const {
    return function < 0 ? 1.0 : functions[function](t);
  }
  /// The factor of the k-th particle of a load at time t.
  double factor(const BodyLoad& load, std::size_t k, double t) const {
    const double g = factor(load.function, t);
    return load.pulses.empty() ? g : g * load.pulses[k](t);
  }
  /// Adds every load's force per volume at time t to f (3 per particle).
  void add_forces(double t, std::vector<double>& f) const;
  /// The loads' power sum_i b_i(t) . du_i V_i on the displacement increments du (3 per particle).
  double power(const std::vector<double>& du, const std::vector<double>& volume, double t) const;
  /// Applies the prescribed components at time t: displacement constraints set u (and the
  /// velocity that moved them there from u_before over dt), velocity constraints set v;
  /// accelerations of constrained components are zero. Without u_before only the accelerations
  /// are set.
  void impose(particles::ParticleSet& q, double t, double dt,
              const std::vector<double>* u_before) const;
  /// Sets the prescribed velocity components at time t again (after the second half kick).
  void keep_velocities(particles::ParticleSet& q, double t) const;
  /// Calls f(k, c, value) for every fixed component of every constraint at time t: k indexes the
  /// component (3 per particle), c is its constraint and value its prescribed displacement (or
  /// velocity) times the time function.
  template <class F> void for_each_fixed(double t, F&& f) const {
    for (const Constraint& c : constraints) {
      const double g = factor(c.function, t);
      for (std::size_t p = 0; p < c.particles.size(); ++p)
        for (int d = 0; d < 3; ++d)
          if (c.fixed[d])
            f(3 * static_cast<std::size_t>(c.particles[p]) + d, c, c.target(p, d) * g);
    }
  }
};

struct StepReport {
  long broken = 0;              // bonds broken in this step (from both ends)
  double strain_energy = 0.0;   // if asked for
  double external_work = 0.0;   // work of the body loads over the step
  double contact_energy = 0.0;  // penalty impactors' and short-range contact's potential energy
  double fracture_energy = 0.0; // strain energy of the bonds broken in this evaluation
  double fracture_work = 0.0;   // half work of the bonds broken before this step, over it
};

/// On a run spread over MPI ranks every function below is collective (each rank calls it): the
/// ghosts are refreshed before the forces, and the step's counts, energies, work and contact
/// impulses are summed over the ranks.
///
/// Accelerations of the particles at their current state: bond forces plus body loads over
/// density (constrained components get zero). Call once before the first step.
StepReport accelerate(Model& m, BondState& s, const Loading& loading, bool with_energy);

/// What a step adds to the bonds and the loads: impactors, the short-range contact of
/// particles, and (when not null) the account of the energy breaking bonds take.
struct Interactions {
  std::vector<Impactor>* impactors = nullptr;
  ShortRangeContact* short_range = nullptr;
  FractureEnergy* fracture = nullptr;
};

/// The same with the interactions: the short-range contact force and the penalty impactors'
/// forces are added after the bond forces, as LAMMPS adds fix indent's (post_force).
StepReport accelerate(Model& m, BondState& s, const Loading& loading, const Interactions& x,
                      bool with_energy);

/// One velocity-Verlet step of length dt with the impactors in contact: the particles' motion
/// and clock move on. The order is LAMMPS's: half kick and drift of particles and impactors,
/// kinematic contact, forces (bonds, short-range contact, penalty impactors), half kick.
StepReport advance(Model& m, BondState& s, const Loading& loading, std::vector<Impactor>& impactors,
                   double dt, bool with_energy);
StepReport advance(Model& m, BondState& s, const Loading& loading, const Interactions& x, double dt,
                   bool with_energy);

/// Kinetic energy sum_i rho_i V_i |v_i|^2 / 2.
double kinetic_energy(const Model& m);

} // namespace mf::pd
