#pragma once
// An SPH body started from a given stress state (a preload computed by another method): the
// density that gives each particle the pressure of its stress through its own equation of state,
// the deviatoric stress, the plastic strain and back stress, and a check of every particle
// against its own yield surface.
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/sph/hydro.hpp"
#include <vector>

namespace mf::sph {

using materials::Vec6;

/// The density at which an equation of state gives pressure p at specific energy e, and the
/// largest density reached that goes with it: the state lies on the loading curve (rho_max = rho)
/// for the laws with a compaction history (tabulated compaction, HJC) and has no damage.
/// Linear polynomial, Mie-Gruneisen and HJC are solved by Newton's method inside a bracket
/// (bisection where a Newton step leaves it) to the last bits of rho; the piecewise-linear
/// compaction curve is inverted on its segment. Below the lowest pressure a law allows in
/// tension (compaction's -tensile_limit, HJC's -T) the density of that limit is returned; the
/// ideal gas and JWL products have no solid state and are refused, as is a pressure beyond the
/// top of a compaction table.
struct EosDensity {
  double rho = 0.0, rho_max = 0.0;
};
EosDensity density_for_pressure(const materials::EquationOfState& eos, double p, double e);

/// What set_initial_state found. A particle is over its yield surface when its von Mises stress q
/// (of S - back stress for J2) exceeds its yield stress Y by more than 1e-9 Y, and on it within
/// 1e-6 Y; worst_ratio is the largest q / Y (Y floored at 1e-12 of the largest stress component,
/// so that a sheared particle of a cohesionless material at zero pressure gives a large, finite
/// ratio). density_mismatch = max |p_EOS(rho, e) + tr(sigma) / 3| / max |sigma|.
struct InitialStateReport {
  int over_surface = 0, on_surface = 0;
  double worst_ratio = 0.0;
  int worst_particle = -1;
  double density_mismatch = 0.0;
  int returned = 0;
};

/// Sets every owned particle's stress state from sigma (Voigt xx yy zz yz xz xy, tension
/// positive, one per owned particle; 2D plane strain passes its sigma_zz): the density from its
/// equation of state so that p = -tr(sigma) / 3 (density_for_pressure, at the particle's own
/// specific energy), rho_max with it, h = h_ref (rho_ref / rho)^(1/dim), the deviatoric stress
/// S = sigma + p I (zero for a fluid), the equivalent plastic strain and back stress (empty
/// vectors: zero), no damage, no failure; mass, energy and motion unchanged. p and c are then
/// refreshed and each particle is checked against its own yield surface (J2 with its hardening,
/// granular Y(p), HJC at its pressure, no damage, the static rate). With return_to_surface a
/// particle over it is brought back radially, along its deviator from the surface's centre (the
/// back stress for J2), with its plastic strain and back stress unchanged: the given state is
/// taken as the truth, and only the part of it the surface cannot hold is dropped. A particle
/// whose plastic strain reaches its material's failure strain is marked failed.
InitialStateReport set_initial_state(Hydro& h, const std::vector<Vec6>& sigma,
                                     const std::vector<double>& plastic_strain,
                                     const std::vector<Vec6>& back_stress, bool return_to_surface);

/// Puts the displacement u (3 per owned particle) on the owned particles at rest (v = 0, a = 0),
/// and refreshes the mirror particles. A fixed particle keeps this displacement: the step moves
/// it with its velocity, which stays 0.
void set_displacement(Hydro& h, const std::vector<double>& u);

} // namespace mf::sph
