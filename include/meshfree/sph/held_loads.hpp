#pragma once
// Loads that stay on through an SPH run: constant surface forces from a traction on a surface
// layer of particles, and the static force that holds a transmitting boundary of a body cut out
// of a stressed medium.
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/particles/particle_set.hpp"
#include "meshfree/sph/hydro.hpp"
#include <string>
#include <vector>

namespace mf::sph {

/// The face area of particle i in a surface layer one particle thick: V / V^(1/dim), its volume
/// over its spacing (the area a blast load or a dashpot acts on).
double face_area(const particles::ParticleSet& P, int i, int dim);

/// Constant forces traction * face_area(i) on each particle of a surface layer (`traction`: 3
/// components, force per area, unused axes 0); fixed particles are left out.
SurfaceForce traction_force(const Hydro& h, const std::string& name,
                            const std::vector<int>& particles, const double traction[3]);

/// Sets the boundary's static force to sigma . n A for each of its particles, n its outward
/// normal, A the particle's face area and sigma = sigma_of_particle[particle] (Voigt xx yy zz yz
/// xz xy, tension positive): the traction the medium beyond the boundary exerted on the body in
/// its initial state, so that the dashpots only see the motion away from it.
void hold_stress(TransmittingBoundary& b, const std::vector<materials::Vec6>& sigma_of_particle);

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
/// added to h.forces, they hold those particles exactly at rest in the current state. A staged
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

} // namespace mf::sph
