#pragma once
// Building blocks of the SPH tests.
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/particle_fields.hpp"

/// Adds an SPH particle at rest at x with reference volume and density.
inline int add(mf::sph::Hydro& s, const double x[3], double volume, double rho, double e, double h,
               int mat, bool fixed = false) {
  return mf::sph::add_particle(s, mf::Vec3(x[0], x[1], x[2]), volume, rho, e, h, mat, fixed);
}
