#pragma once
// Loads that stay on through an SPH run: constant surface forces from a traction on a surface
// layer of particles, and the static force that holds a transmitting boundary of a body cut out
// of a stressed medium.
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/particles/particle_set.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/surface_force.hpp"
#include "meshfree/sph/transmitting_boundary.hpp"
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

} // namespace mf::sph
