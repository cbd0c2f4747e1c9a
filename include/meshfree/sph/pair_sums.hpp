#pragma once
// The pair sums of the SPH rates: continuity, momentum and energy ([Altafi 2018] eqs. 3-41, 3-48
// and 3-64) with Monaghan's viscosity, the deviatoric stress with the artificial stress, the
// inter-material penalty, and the velocity gradient with the Jaumann rate of the stress.
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/rates.hpp"

namespace mf::sph {

/// Sums the pair terms of every owned particle into r.dv (with gravity and damping; 0 for a fixed
/// particle), r.drho and r.de and, with `solids`, r.grad_v and r.dS (zeros where a particle has no
/// strength). r must hold the current positions x, p / rho^2, 1 / rho^2, m / rho, the correction
/// matrices, artificial stresses and spacings when they are used, the shear moduli with `solids`,
/// and zeroed outputs. By default each pair is evaluated once from s.neighbours.half_pairs and its
/// terms go to both ends (Newton's third law); with settings.deterministic every row of
/// s.neighbours.pairs is summed whole, in its order.
void sum_pairs(const Hydro& s, Rates& r, bool solids);

} // namespace mf::sph
