#include "meshfree/loads/blast.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <vector>

namespace mf::loads {

namespace {

enum class Quantity {
  incident_overpressure,
  incident_impulse,
  normal_reflected_overpressure,
  normal_reflected_impulse,
  shock_front_velocity,
  arrival_time,
  positive_phase_duration
};

/// One segment of a Kingery-Bulmash fit: on z_min <= Z <= z_max,
/// log10 Y = sum_i C_i U^i with U = K0 + K1 log10 Z; Y in kPa, kPa ms / kg^(1/3),
/// ms / kg^(1/3) or km/s (`scaled`: times W^(1/3)).
struct Segment {
  Burst burst;
  Quantity quantity;
  double z_min, z_max, k0, k1;
  std::vector<double> c;
  bool scaled;
};

// Kingery & Bulmash (1984), metric coefficients as tabulated for UFC 3-340-02 / NATO AASTP-1;
// reference/blast/ keeps them as a table with values and the Swisdak (1994) cross-check.
const std::vector<Segment>& segments() {
  using B = Burst;
  using Q = Quantity;
  constexpr B Spherical = B::SphericalFreeAir;
  constexpr B Hemispherical = B::HemisphericalSurface;
  static const std::vector<Segment> table = {
      {Spherical,
       Q::incident_overpressure,
       0.0531,
       40,
       -0.214362789151,
       1.35034249993,
       {2.611368669, -1.69012801396, 0.00804973591951, 0.336743114941, -0.00516226351334,
        -0.0809228619888, -0.00478507266747, 0.00793030472242, 0.0007684469735},
       false},
      {Spherical,
       Q::incident_impulse,
       0.0531,
       0.792,
       2.34723921354,
       3.24299066475,
       {2.38830516757, -0.443749377691, 0.168825414684, 0.0348138030308, -0.010435192824},
       true},
      {Spherical,
       Q::incident_impulse,
       0.792,
       40,
       -1.75305660315,
       2.30629231803,
       {1.55197227115, -0.40463292088, -0.0142721946082, 0.00912366316617, -0.0006750681404,
        -0.00800863718901, 0.00314819515931, 0.00152044783382, -0.0007470265899},
       true},
      {Spherical,
       Q::normal_reflected_overpressure,
       0.0531,
       40,
       -0.214362789151,
       1.35034249993,
       {3.22958031387, -2.21400538997, 0.035119031446, 0.657599992109, 0.0141818951887,
        -0.243076636231, -0.0158699803158, 0.0492741184234, 0.00227639644004, -0.00397126276058},
       false},
      {Spherical,
       Q::normal_reflected_impulse,
       0.0531,
       40,
       -0.204004553231,
       1.37882996018,
       {2.55875660396, -0.903118886091, 0.101771877942, -0.0242139751146},
       true},
      {Spherical,
       Q::shock_front_velocity,
       0.0531,
       40,
       -0.214362789151,
       1.35034249993,
       {-0.144615443471, -0.650507560471, 0.291320654009, 0.307916322787, -0.183361123489,
        -0.197740454538, 0.0909119559768, 0.0898926178054, -0.0287370990248, -0.0248730221702,
        0.00496311705671, 0.00372242076361, -0.0003533736952, -0.0002292913709},
       false},
      {Spherical,
       Q::arrival_time,
       0.0531,
       40,
       -0.253273111999,
       1.37407043777,
       {0.0720707787637, 1.36456871214, -0.0570035692784, -0.182832224796, 0.0118851436014,
        0.0432648687627, -0.0007997367834, -0.00436073555033},
       true},
      {Spherical,
       Q::positive_phase_duration,
       0.147,
       0.888,
       2.26367268496,
       5.11588554305,
       {-0.686608550419, 0.164953518069, 0.127788499497, 0.00291430135946, 0.00187957449227,
        0.0173413962543, 0.00269739758043, -0.00361976502798, -0.00100926577934},
       true},
      {Spherical,
       Q::positive_phase_duration,
       0.888,
       2.28,
       -1.33361206714,
       9.2996288611,
       {0.23031841078, -0.0297944268969, 0.0306329542941, 0.0183405574074, -0.0173964666286,
        -0.00106321963576, 0.0056206003128, 0.0001618217499, -0.0006860188944},
       true},
      {Spherical,
       Q::positive_phase_duration,
       2.28,
       40,
       -3.13005805346,
       3.1524725364,
       {0.621036276475, 0.0967031995552, -0.00801302059667, 0.00482705779732, 0.00187587272287,
        -0.00246738509321, -0.000841116668, 0.0006193291052},
       true},
      {Hemispherical,
       Q::incident_overpressure,
       0.0674,
       40,
       -0.214362789151,
       1.35034249993,
       {2.78076916577, -1.6958988741, -0.154159376846, 0.514060730593, 0.0988534365274,
        -0.293912623038, -0.0268112345019, 0.109097496421, 0.00162846756311, -0.0214631030242,
        0.0001456723382, 0.00167847752266},
       false},
      {Hemispherical,
       Q::incident_impulse,
       0.0674,
       0.955,
       2.06761908721,
       3.0760329666,
       {2.52455620925, -0.502992763686, 0.171335645235, 0.0450176963051, -0.0118964626402},
       true},
      {Hemispherical,
       Q::incident_impulse,
       0.955,
       40,
       -1.94708846747,
       2.40697745406,
       {1.67281645863, -0.384519026965, -0.0260816706301, 0.00595798753822, 0.0145445261077,
        -0.00663289334734, -0.00284189327204, 0.0013644816227},
       true},
      {Hemispherical,
       Q::normal_reflected_overpressure,
       0.0674,
       40,
       -0.240657322658,
       1.36637719229,
       {3.40283217581, -2.21030870597, -0.218536586295, 0.895319589372, 0.24989009775,
        -0.569249436807, -0.11791682383, 0.224131161411, 0.0245620259375, -0.0455116002694,
        -0.00190930738887, 0.00361471193389},
       false},
      {Hemispherical,
       Q::normal_reflected_impulse,
       0.0674,
       40,
       -0.246208804814,
       1.33422049854,
       {2.70588058103, -0.949516092853, 0.112136118689, -0.0250659183287},
       true},
      {Hemispherical,
       Q::shock_front_velocity,
       0.0674,
       40,
       -0.202425716178,
       1.37784223635,
       {-0.06621072854, -0.698029762594, 0.158916781906, 0.443812098136, -0.113402023921,
        -0.369887075049, 0.129230567449, 0.19857981197, -0.0867636217397, -0.0620391900135,
        0.0307482926566, 0.0102657234407, -0.00546533250772, -0.000693180974, 0.0003847494916},
       false},
      {Hemispherical,
       Q::arrival_time,
       0.0674,
       40,
       -0.202425716178,
       1.37784223635,
       {-0.0591634288046, 1.35706496258, 0.052492798645, -0.196563954086, -0.0601770052288,
        0.0696360270891, 0.0215297490092, -0.0161658930785, -0.00232531970294, 0.00147752067524},
       true},
      {Hemispherical,
       Q::positive_phase_duration,
       0.178,
       1.01,
       1.92946154068,
       5.25099193925,
       {-0.614227603559, 0.130143717675, 0.134872511954, 0.0391574276906, -0.00475933664702,
        -0.00428144598008},
       true},
      {Hemispherical,
       Q::positive_phase_duration,
       1.01,
       2.78,
       -2.12492525216,
       9.2996288611,
       {0.315409245784, -0.0297944268976, 0.030632954288, 0.0183405574086, -0.0173964666211,
        -0.00106321963633, 0.00562060030977, 0.0001618217499, -0.0006860188944},
       true},
      {Hemispherical,
       Q::positive_phase_duration,
       2.78,
       40,
       -3.53626218091,
       3.46349745571,
       {0.686906642409, 0.0933035304009, -0.0005849420883, -0.00226884995013, -0.00295908591505,
        0.00148029868929},
       true},
  };
  return table;
}

/// Y(Z) of a quantity, from the segment that holds Z (the nearest end outside every segment).
double fit(Burst burst, Quantity q, double z) {
  const Segment* best = nullptr;
  double z_eval = z;
  for (const Segment& s : segments()) {
    if (s.burst != burst || s.quantity != q) continue;
    if (z >= s.z_min && z <= s.z_max) {
      best = &s;
      z_eval = z;
      break;
    }
    const double end = z < s.z_min ? s.z_min : s.z_max;
    if (!best || std::abs(end - z) < std::abs(z_eval - z)) best = &s, z_eval = end;
  }
  const double u = best->k0 + best->k1 * std::log10(z_eval);
  double log_y = 0.0, power = 1.0;
  for (double c : best->c) {
    log_y += c * power;
    power *= u;
  }
  return std::pow(10.0, log_y);
}

} // namespace

std::pair<double, double> kingery_bulmash_range(Burst burst) {
  return burst == Burst::SphericalFreeAir ? std::make_pair(0.0531, 40.0)
                                          : std::make_pair(0.0674, 40.0);
}

BlastParameters kingery_bulmash(Burst burst, double tnt_mass, double distance) {
  MF_REQUIRE(tnt_mass > 0.0, "Kingery-Bulmash: the charge mass must be positive, got ", tnt_mass);
  const double w3 = std::cbrt(tnt_mass);
  const double z = distance / w3;
  const auto [z_lo, z_hi] = kingery_bulmash_range(burst);
  MF_REQUIRE(z >= z_lo && z <= z_hi, "Kingery-Bulmash: scaled distance ", z,
             " m/kg^(1/3) (R = ", distance, " m, W = ", tnt_mass, " kg) is outside the fit's ",
             z_lo, "..", z_hi);
  using Q = Quantity;
  BlastParameters b;
  b.scaled_distance = z;
  b.incident_pressure = 1e3 * fit(burst, Q::incident_overpressure, z);
  b.reflected_pressure = 1e3 * fit(burst, Q::normal_reflected_overpressure, z);
  // kPa ms = Pa s.
  b.incident_impulse = w3 * fit(burst, Q::incident_impulse, z);
  b.reflected_impulse = w3 * fit(burst, Q::normal_reflected_impulse, z);
  b.arrival_time = 1e-3 * w3 * fit(burst, Q::arrival_time, z);
  b.positive_duration = 1e-3 * w3 * fit(burst, Q::positive_phase_duration, z);
  b.shock_speed = 1e3 * fit(burst, Q::shock_front_velocity, z);
  return b;
}

double Friedlander::operator()(double t) const {
  const double s = t - arrival;
  if (s < 0.0 || s > duration) return 0.0;
  return peak * (1.0 - s / duration) * std::exp(-decay * s / duration);
}

namespace {
/// I / (P t_d) of a Friedlander phase with decay b: 1/b - (1 - e^-b)/b^2 (1/2 - b/6 + ... near 0).
double impulse_ratio(double b) {
  if (b < 1e-4) return 0.5 - b / 6.0 + b * b / 24.0;
  return 1.0 / b - (1.0 - std::exp(-b)) / (b * b);
}
} // namespace

double Friedlander::impulse() const {
  return peak * duration * impulse_ratio(decay);
}

double friedlander_decay(double peak, double duration, double impulse) {
  MF_REQUIRE(peak > 0.0 && duration > 0.0 && impulse > 0.0,
             "Friedlander fit: peak, duration and impulse must be positive, got ", peak, ", ",
             duration, ", ", impulse);
  const double ratio = impulse / (peak * duration);
  if (ratio >= 0.5) return 0.0;
  // impulse_ratio decreases from 1/2 at b = 0 to 0 as 1/b: bisection on a bracket.
  double lo = 0.0, hi = 1.0;
  while (impulse_ratio(hi) > ratio) hi *= 2.0;
  for (int k = 0; k < 200 && hi - lo > 1e-14 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (impulse_ratio(mid) > ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Friedlander blast_pulse(const BlastParameters& b, double cos_incidence) {
  double peak = b.incident_pressure, impulse = b.incident_impulse;
  if (cos_incidence > 0.0) {
    const double c = std::min(cos_incidence, 1.0), c2 = c * c;
    const double side = 1.0 + c2 - 2.0 * c;
    peak = b.reflected_pressure * c2 + b.incident_pressure * side;
    impulse = b.reflected_impulse * c2 + b.incident_impulse * side;
  }
  Friedlander f;
  f.arrival = b.arrival_time;
  f.duration = b.positive_duration;
  f.peak = peak;
  f.decay = friedlander_decay(peak, b.positive_duration, impulse);
  return f;
}

} // namespace mf::loads
