#pragma once
// Time stepping of an SPH run: the CFL bound, the midpoint predictor-corrector step and the
// energies.
#include "meshfree/sph/hydro.hpp"

namespace mf::sph {

/// The CFL step courant * min_i h_i / (c_i + |v_i|) and the particle that sets it.
double stable_step(const Hydro& s, int* limiting = nullptr);

/// One midpoint predictor-corrector step of length dt (second order).
void advance(Hydro& s, double dt);

/// Kinetic and internal energy of all particles.
struct Energies {
  double kinetic = 0.0, internal = 0.0;
  double total() const { return kinetic + internal; }
};
Energies energies(const Hydro& s);

} // namespace mf::sph
