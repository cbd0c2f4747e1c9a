#pragma once
// Symmetry planes by mirror particles (Libersky & Petschek 1991, [Altafi 2018] type-II virtual
// particles): the particles within reach of a plane are mirrored across it, with the normal
// velocity and the shear stresses on the plane reversed.
#include "meshfree/sph/hydro.hpp"
#include <vector>

namespace mf::sph {

/// Drops the old mirror particles and mirrors every particle (owned or a remote ghost) within
/// `band` of each plane, the images of earlier planes included (corners of two or three planes).
void rebuild_mirrors(Hydro& s, double band);

/// Copies every mirror particle's state from its source, mirrored.
void refresh_mirrors(Hydro& s);

/// Fills the mirror particles' 3x3 matrices (9 per particle, row-major) from their sources.
void mirror_matrices(const Hydro& s, std::vector<double>& C);

/// Fills the mirror particles' symmetric tensors (6 per particle, Voigt) from their sources.
void mirror_voigt(const Hydro& s, std::vector<double>& T);

} // namespace mf::sph
