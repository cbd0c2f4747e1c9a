#pragma once
// Rates of an SPH run: the continuity, momentum and energy equations ([Altafi 2018] eqs. 3-41,
// 3-48 and 3-64) with Monaghan's viscosity, the Jaumann rate of the deviatoric stress, the
// kernel-gradient correction, the artificial stress, the inter-material penalty, gravity,
// damping, and the forces of the boundary conditions (sph/condition.hpp).
#include "meshfree/sph/hydro.hpp"
#include <vector>

namespace mf::sph {

/// What a pair reads of each of its particles, in one record per particle, so that a partner's
/// values come from two cache lines rather than from one line per array: the velocity, m, the
/// volume m / rho, p / rho^2, c, rho and (solids) T = S / rho^2 in Voigt order.
struct Record {
  enum : int { v = 0, mass = 3, volume = 4, p_rho2 = 5, c = 6, rho = 7, T = 8, size = 16 };
};

struct Rates {
  std::vector<double> dv, drho, de, dS;
  std::vector<double> grad_v;     // 9 per particle (solids): L_ab = d v_a / d x_b
  std::vector<double> correction; // 9 per particle: the kernel-gradient correction matrix
  std::vector<double> art_stress; // 6 per particle: the artificial stress R (Voigt, like S)
  std::vector<double> spacing;    // initial spacing per particle (artificial stress, penalty)
  std::vector<double> x;          // current positions X + u, 3 per particle, ghosts included
  std::vector<double> xh;         // x, y, z and h per particle, ghosts included
  std::vector<double> records;    // Record::size per particle, ghosts included
  std::vector<double> shear;      // shear modulus per owned particle (solids), -1: no strength
};

/// Rates of velocity, density and energy (and deviatoric stress, for solids) at the current
/// state.
void compute_rates(const Hydro& s, Rates& r);

/// The forces of the boundary conditions at the current state, particle by particle (a particle
/// may appear more than once); gravity and damping are not among them.
void external_forces(const Hydro& s, std::vector<int>& who, std::vector<double>& force);

} // namespace mf::sph
