#pragma once
// Empirical air-blast loading of a TNT charge: the Kingery-Bulmash fits (the basis of CONWEP and
// of UFC 3-340-02) for a spherical free-air burst and a hemispherical surface burst, the
// Friedlander pressure history fitted to the impulse, and the pressure on a face at an angle of
// incidence.
#include <utility>

namespace mf::loads {

enum class Burst { SphericalFreeAir, HemisphericalSurface };

/// Peak values of the positive phase at one stand-off, SI units.
struct BlastParameters {
  double scaled_distance = 0.0;    // Z = R / W^(1/3) [m/kg^(1/3)]
  double incident_pressure = 0.0;  // side-on peak overpressure P_so [Pa]
  double reflected_pressure = 0.0; // normally reflected peak overpressure P_r [Pa]
  double incident_impulse = 0.0;   // I_so [Pa s]
  double reflected_impulse = 0.0;  // I_r [Pa s]
  double arrival_time = 0.0;       // t_a [s]
  double positive_duration = 0.0;  // t_d [s]
  double shock_speed = 0.0;        // U [m/s]
};

/// Scaled distances where every fit of the burst holds [m/kg^(1/3)]. Below the range of the
/// duration fit (0.147 free air, 0.178 surface) the duration is its value at that end.
std::pair<double, double> kingery_bulmash_range(Burst burst);

/// The Kingery-Bulmash parameters of `tnt_mass` kg of TNT at `distance` m (Kingery & Bulmash
/// 1984, ARBRL-TR-02555; metric polynomials log10 Y = sum_i C_i U^i, U = K0 + K1 log10 Z, as
/// tabulated for UFC 3-340-02 and NATO AASTP-1). Impulses and times scale with W^(1/3). Throws
/// mf::Error outside kingery_bulmash_range().
BlastParameters kingery_bulmash(Burst burst, double tnt_mass, double distance);

/// A Friedlander positive phase: p(t) = P (1 - s/t_d) exp(-b s/t_d), s = t - t_a, for
/// 0 <= s <= t_d, and 0 elsewhere (the negative phase is left out).
struct Friedlander {
  double arrival = 0.0, duration = 0.0, peak = 0.0, decay = 0.0;
  double operator()(double t) const;
  /// P t_d (1/b - (1 - e^-b)/b^2); P t_d / 2 for b = 0.
  double impulse() const;
};

/// The decay coefficient b >= 0 whose Friedlander phase of `peak` and `duration` carries
/// `impulse`. A ratio I / (P t_d) >= 1/2 (more than the triangle holds) gives b = 0.
double friedlander_decay(double peak, double duration, double impulse);

/// The pressure history on a face whose normal makes the angle of incidence alpha with the ray
/// from the charge (cos_incidence = cos alpha; <= 0 for a face turned away): peak and impulse are
/// P_r cos^2 a + P_so (1 + cos^2 a - 2 cos a) (Randers-Pehrson & Bannister 1997, ARL-TR-1310, the
/// CONWEP model of LS-DYNA's *LOAD_BLAST), P_so alone for a face turned away; the duration is
/// the incident one and the decay is fitted to the impulse.
Friedlander blast_pulse(const BlastParameters& b, double cos_incidence);

} // namespace mf::loads
