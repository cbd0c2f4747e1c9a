#pragma once
// Time stepping of an SPH run: the CFL bound, the midpoint predictor-corrector step and the
// energies.
#include "meshfree/sph/hydro.hpp"

namespace mf::sph {

/// The CFL step courant * min_i h_i / (c_i + |v_i|) over every rank, and the particle that sets
/// it (its local index on the rank that holds it, -1 on the others). Collective.
double stable_step(const Hydro& s, int* limiting = nullptr);

/// One midpoint predictor-corrector step of length dt (second order). Collective.
void advance(Hydro& s, double dt);

/// Kinetic and internal energy of the owned particles of every rank. Collective.
struct Energies {
  double kinetic = 0.0, internal = 0.0;
  double total() const { return kinetic + internal; }
};
Energies energies(const Hydro& s);

} // namespace mf::sph
