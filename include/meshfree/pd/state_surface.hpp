#pragma once
// The position-aware influence of a state-based (LPS) body: its surface correction. A particle
// whose family a surface cuts has an anisotropic family: under a homogeneous strain its LPS
// dilatation is not the strain's trace nor its deviatoric energy mu e^d : e^d, which moves a
// free edge's layers and, through them, the body (a plane-strain strip of 40 x 20 particles
// under a traction: its interior, two horizons inside the edges, moves 5.0% of u; 0.24% with the
// correction, tests/unit/stages/test_held_conditions.cpp). After
// Mitchell, Silling & Littlewood's position-aware linear solid (PALS, 2015), each particle i
// takes its own influence for the two parts, the LPS's scaled by forms of the bond's direction n:
//   dilatation   omega_i<xi> = omega<xi> (n . Lambda_i . n),
//   deviatoric   beta_i<xi>  = mu omega<xi> sum_{a<=b} c_ab p_a p_b,  p_a = n . D_a . n,
// over an orthonormal basis D_a of deviatoric tensors, with Lambda_i and c_i solved from its
// family so that theta_i = sum_j omega_i |xi| e w_ij is the trace of every homogeneous strain
// (sum_j omega_i xi xi w_ij = I) and (1/2) sum_j beta_i (e^d)^2 w_ij its mu e^d : e^d
// (sum_j beta_i |xi|^2 p_a p_b w_ij = 2 mu delta_ab): Gram systems of 3 and 3 unknowns in a
// plane, 6 and 15 in 3D. The energy
//   W_i = kappa theta_i^2 / 2 + (1/2) sum_j beta_i (e - theta_i |xi| / d)^2 w_ij
// gives the force state
//   t_i = omega_i |xi| (kappa theta_i - Q_i / d) + beta_i e^d,  Q_i = sum_j beta_i e^d |xi| w_ij,
// (Q_i = 0 in the LPS, whose weights make it vanish). The forms contain the LPS's weights, which
// they reproduce where a family is whole and isotropic; on a lattice they also remove the
// family's cubic anisotropy of the shear modulus (C44 -0.15 to -0.87% in 3D, -2.6% in a plane at
// delta = 3 dx). The factors over the LPS's, omega_i / (omega d / m_i) and beta_i / (a mu omega
// / m_i), are the bond classes' dil and dev (pd/model.hpp); the influence is set once, over the
// family after pre-cracks, as the weighted volumes are. Elastic LPS only: the EPS's plastic
// return is Mitchell's, on the LPS's weights.
#include "meshfree/pd/model.hpp"
#include <vector>

namespace mf::pd {

/// Sets every bond's position-aware factors from the families intact in `s` (owned and ghost
/// particles' coefficients; collective) and marks the model. Call after set_weighted_volumes.
/// Returns the particles whose family was too small to fix both forms (they keep the LPS's
/// influence: a family of collinear or too few bonds), summed over the ranks.
long apply_position_aware_influence(Model& m, const BondState& s);

/// state_fictitious_density (pd/state_based.hpp) for a position-aware body: the same Gershgorin
/// row sums, each bond's terms with its factors and the Q_i coupling added. With every factor 1
/// and no Q_i it is that bound summed in another order; the LPS keeps its own function so that
/// its relaxations stay bit for bit what they were.
std::vector<double> position_aware_fictitious_density(const Model& m, const BondState& s);

} // namespace mf::pd
