#pragma once
// How well velocity Verlet keeps a free peridynamic body's energy: |KE + SE - E0| / E0 every
// `every` steps, the largest over the run and over its first and last thousand steps (a drift
// shows as the last larger than the first).
#include "meshfree/pd/dynamics.hpp"
#include <algorithm>
#include <cmath>
#include <vector>

namespace mf::test {

struct EnergyDrift {
  double worst = 0.0, first = 0.0, last = 0.0;
};

inline EnergyDrift energy_drift(pd::Model& m, pd::BondState& s, double dt, int steps, int every) {
  const pd::Loading none;
  std::vector<pd::Impactor> no_impactors;
  const double e0 = pd::kinetic_energy(m) + pd::accelerate(m, s, none, true).strain_energy;
  EnergyDrift d;
  for (int step = 1; step <= steps; ++step) {
    const bool check = step % every == 0;
    const pd::StepReport r = pd::advance(m, s, none, no_impactors, dt, check);
    if (!check) continue;
    const double e = std::abs(pd::kinetic_energy(m) + r.strain_energy - e0) / e0;
    d.worst = std::max(d.worst, e);
    if (step <= 1000) d.first = std::max(d.first, e);
    if (step > steps - 1000) d.last = std::max(d.last, e);
  }
  return d;
}

} // namespace mf::test
