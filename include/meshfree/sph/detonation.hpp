#pragma once
// Detonation of explosives (JWL materials): lighting times of a programmed burn and the burn
// fraction that scales the products' pressure.
#include "meshfree/materials/equation_of_state.hpp"
#include "meshfree/sph/hydro.hpp"
#include <algorithm>

namespace mf::sph {

/// Lighting times for a detonation at point `at` (distance / D_CJ) of every particle of an
/// explosive (JWL) material; other particles never burn. An explosive with an unreacted
/// equation of state is lit on schedule only within 2 h of the point (the booster); the shock
/// lights the rest.
void light_from_point(Hydro& s, const double at[3]);

/// The same for a detonation plane through `at` with unit normal `normal`: lighting time =
/// distance to the plane / D_CJ (a plane wave generator).
void light_from_plane(Hydro& s, const double at[3], const double normal[3]);

/// Burn fraction F = max(F_programmed, F_beta) of a particle lit at light_time (Wilkins 1964;
/// LS-DYNA's *MAT_HIGH_EXPLOSIVE_BURN): the lit time over the burn width,
/// (t - t_l) D / (burn_width h), or the compression toward the CJ state, (1 - V) / (1 - V_CJ)
/// with 1 - V_CJ = P_CJ / (rho0 D^2), clamped to [0, 1]. With an unreacted equation of state the
/// shock has compressed the particle before it lights, and the burn follows its lighting time
/// only (a ZND front).
inline double burn_fraction(const materials::JwlExplosive& x, double time, double light_time,
                            double h, double rho, double burn_width) {
  const materials::Jwl& j = x.jwl;
  const double programmed = (time - light_time) * j.detonation_speed / (burn_width * h);
  const double beta =
      (1.0 - j.rho0 / rho) * j.rho0 * j.detonation_speed * j.detonation_speed / j.cj_pressure;
  return std::clamp(x.unreacted ? programmed : std::max(programmed, beta), 0.0, 1.0);
}

} // namespace mf::sph
