#pragma once
// The energy that breaking bonds take out of a peridynamic body. A bond that breaks in a force
// evaluation at positions y^n counts its strain energy and its force in that evaluation
// (pd/forces.hpp) and neither after it. In velocity Verlet its force still does its half of the
// trapezoidal work (F^n + F^{n+1}) . dy / 2 of the next step (the half kick after the
// evaluation), so what the body's energy loses with the bond is its energy e(y^n) less that
// half work W = F^n . (y^{n+1} - y^n) / 2, counted once the next drift is known. e is the
// strain energy's own term V_i w_ij w(s_ij) / 2 from each end. A state-based body's break
// changes the energy and forces of the neighbourhood around it: e and F are differences of the
// whole body's (pd/state_based.hpp, state_forces_kept).
#include "meshfree/pd/model.hpp"
#include <vector>

namespace mf::pd {

class FractureEnergy {
public:
  /// The strain energy, at positions y, of the bonds intact in `before` and broken in s.intact;
  /// remembers their forces for work_over_step.
  double broken(const Model& m, const BondState& s, const std::vector<unsigned char>& before,
                const std::vector<double>& y);

  /// Half the work, over a step with displacement increments du (3 per particle), of the forces
  /// of the bonds broken in the evaluation before it; forgets them.
  double work_over_step(const std::vector<double>& du);

  /// The bonds broken in the last evaluation, not yet accounted for (a checkpoint keeps them).
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("particle", particle_), visit("force", force_);
  }
  /// Three forces per particle, each one of the `owned` particles.
  bool consistent(int owned) const {
    if (force_.size() != 3 * particle_.size()) return false;
    for (const int i : particle_)
      if (i < 0 || i >= owned) return false;
    return true;
  }

private:
  /// broken() for a state-based body.
  double broken_states(const Model& m, const BondState& s, const std::vector<unsigned char>& before,
                       const std::vector<double>& y);
  std::vector<int> particle_; // particles with a bond broken in the last evaluation
  std::vector<double> force_; // their broken bonds' force (3 per entry), not per volume
};

} // namespace mf::pd
