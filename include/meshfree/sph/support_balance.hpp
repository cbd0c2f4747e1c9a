#pragma once
// A body held at rest in a stressed state it was started in (the SPH stage of a staged run): the
// out-of-balance forces its SPH sums leave there, the constant forces that balance them, and how
// large what is left is against the body's own forces. What is balanced is what the SPH sums of
// a transferred stress leave unbalanced where the solution it came from is in equilibrium:
// truncated kernels at free surfaces that are not straight (a hole stepped by the lattice),
// stress gradients the particles resolve differently, the plastic zone's kinks. Constant forces
// -m_i a_i hold that state at rest without moving it: a settle (damped motion to the particles'
// own equilibrium) would change the transferred stress instead (by 7% in a gripped homogeneous
// block).
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/surface_force.hpp"
#include <string>
#include <vector>

namespace mf::sph {

/// The out-of-balance force m_i a_i of every owned particle at the current state held at rest:
/// the SPH internal forces, gravity and every load and boundary force at the current instant
/// (the body's velocities are taken as they are; at rest the dashpots add nothing), 3 per owned
/// particle; 0 for fixed particles.
std::vector<double> out_of_balance(Hydro& h);

/// The owned particles within kernel reach (r < h_i + h_j) of a layer of particles, the layer
/// included, ascending: the band over which SPH spreads the traction of a face. A uniform stress
/// loads every particle whose kernel the surface truncates (Monaghan 2005, Rep. Prog. Phys. 68: the
/// kernel sums are incomplete within 2h of a free surface), not only the outer layer.
std::vector<int> within_reach(Hydro& h, const std::vector<int>& layer);

/// Constant forces -m_i a_i on the given particles, from out_of_balance at the current state:
/// added to h.conditions, they hold those particles exactly at rest in the current state. A staged
/// run balances every particle but those near a released condition with it: the outer layer of
/// a held face carries its traction t A while SPH spreads a stress's surface force over the
/// kernel's reach, and stepped surfaces and gradients leave residuals of their own.
///
/// With take_resultant, the resultant of the out-of-balance forces of all the other owned
/// particles is spread over the given ones too, in proportion to their mass, so that no net
/// force is left on the body: a body resting on transmitting boundaries has no stiffness against
/// rigid motion (a dashpot has none), and whatever net force the discretisation leaves would
/// drive it at the constant speed F / (rho c A).
SurfaceForce balancing_force(Hydro& h, const std::string& name, const std::vector<int>& particles,
                             bool take_resultant = false);

/// The scale of the out-of-balance forces: the largest held force on a particle (the conditions'
/// Condition::largest_held_force, gravity), or the largest stress
/// component of `sigma` (one per owned particle, Voigt, tension positive) times a particle's face
/// area.
double largest_force(const Hydro& h, const std::vector<materials::Vec6>& sigma);

/// The largest out-of-balance force of a free particle at the current state held at rest.
double worst_out_of_balance(Hydro& h);

/// The worst out-of-balance of a body held at rest, over the scale of its forces (largest_force),
/// before and after its balancing force.
struct RestBalance {
  double before = 0.0, after = 0.0;
};

/// Holds the body at rest in its current state of stress `sigma` (one per owned particle): the
/// transmitting boundaries `held` (their places among the body's transmitting boundaries, in the
/// list's order) take the static force of sigma (hold_stress), and then the
/// particles `balanced` the balancing force "transfer_balance" (added to h.conditions). Every held
/// boundary takes its static force before the balance is computed: a balance taken while a
/// boundary still lacks its static force would carry its share of the body's weight and stress.
RestBalance hold_at_rest(Hydro& h, const std::vector<materials::Vec6>& sigma,
                         const std::vector<int>& held, const std::vector<int>& balanced);

} // namespace mf::sph
