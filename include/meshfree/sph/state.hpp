#pragma once
// The particles' state from their density, energy and stress: smoothing lengths, pressures and
// sound speeds (equations of state), and the deviatoric stress returned to each strength model's
// yield surface. Each material's laws are dispatched once for all of its particles.
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/rates.hpp"
#include <vector>

namespace mf::sph {

/// Smoothing lengths, pressures and sound speeds from density and energy at time t; the
/// pressure of an explosive particle is the JWL pressure times its burn fraction
/// (sph/detonation.hpp).
void update_state(Hydro& s);

/// The stress history at the start of a step, from which each stage's update starts.
struct StressHistory {
  std::vector<double> S, back_stress, alpha, damage;
};
StressHistory stress_history(const Hydro& s);

/// S = S0 + dt dS, returned radially to the yield surface of the particle's model at its current
/// pressure; the plastic strain, back stress and damage grow from their values at the start of
/// the step.
void update_stress(Hydro& s, const StressHistory& start, const Rates& r, double dt);

/// Marks the particles whose damage or plastic strain has reached failure, and commits the
/// largest density reached.
void commit_history(Hydro& s);

} // namespace mf::sph
