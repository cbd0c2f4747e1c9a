// Empirical blast loads: the Kingery-Bulmash fits against Swisdak's independent fits of the same
// trials (hemispherical surface burst), against the Rankine-Hugoniot relations of a shock in air
// (spherical free-air burst, weak shocks), cube-root scaling, the Friedlander fit to an impulse,
// and the pressure at an angle of incidence.
#include "meshfree/core/error.hpp"
#include "meshfree/loads/blast.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

using namespace mf;
using loads::Burst;

namespace {

/// Swisdak (1994), "Simplified Kingery airblast calculations", 26th DoD Explosives Safety
/// Seminar, Table 1 (hemispherical surface burst of TNT, SI): Y = exp(sum_k c_k (ln Z)^k) on
/// each range of Z. Units: kPa, kPa ms / kg^(1/3), ms / kg^(1/3), km/s.
struct SwisdakRange {
  double z_min, z_max;
  std::vector<double> c;
};

const std::map<std::string, std::vector<SwisdakRange>>& swisdak() {
  static const std::map<std::string, std::vector<SwisdakRange>> table = {
      {"arrival_time",
       {{0.06, 1.5, {-0.7604, 1.8058, 0.1257, -0.0437, -0.031, -0.00669}},
        {1.5, 40, {-0.7137, 1.5732, 0.5561, -0.4213, 0.1054, -0.00929}}}},
      {"incident_overpressure",
       {{0.2, 2.9, {7.2106, -2.1069, -0.3229, 0.1117, 0.0685}},
        {2.9, 23.8, {7.5938, -3.0523, 0.40977, 0.0261, -0.01267}},
        {23.8, 198.5, {6.0536, -1.4066}}}},
      {"normal_reflected_overpressure",
       {{0.06, 2.0, {9.006, -2.6893, -0.6295, 0.1011, 0.29255, 0.13505, 0.019736}},
        {2.0, 40, {8.8396, -1.733, -2.64, 2.293, -0.8232, 0.14247, -0.0099}}}},
      {"positive_phase_duration",
       {{0.2, 1.02, {0.5426, 3.2299, -1.5931, -5.9667, -4.0815, -0.9149}},
        {1.02, 2.8, {0.544, 2.7082, -9.7354, 14.3425, -9.7791, 2.8535}},
        {2.8, 40, {-2.4608, 7.1639, -5.6215, 2.2711, -0.44994, 0.03486}}}},
      {"incident_impulse",
       {{0.2, 0.96, {5.522, 1.117, 0.6, -0.292, -0.087}},
        {0.96, 2.38, {5.465, -0.308, -1.464, 1.362, -0.432}},
        {2.38, 33.7, {5.2749, -0.4677, -0.2499, 0.0588, -0.00554}},
        {33.7, 158.7, {5.9825, -1.062}}}},
      {"normal_reflected_impulse", {{0.06, 40, {6.7853, -1.3466, 0.101, -0.01123}}}},
      {"shock_front_velocity",
       {{0.06, 1.5, {0.1794, -0.956, -0.0866, 0.109, 0.0699, 0.01218}},
        {1.5, 40, {0.2597, -1.326, 0.3767, 0.0396, -0.0351, 0.00432}}}},
  };
  return table;
}

double swisdak_value(const std::string& quantity, double z) {
  for (const SwisdakRange& r : swisdak().at(quantity))
    if (z >= r.z_min && z <= r.z_max) {
      const double x = std::log(z);
      double s = 0.0, p = 1.0;
      for (double c : r.c) s += c * p, p *= x;
      return std::exp(s);
    }
  throw std::runtime_error("no Swisdak range for " + quantity);
}

double rel(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

} // namespace

TEST_CASE("Kingery-Bulmash surface burst matches Swisdak's independent fits", "[blast]") {
  const double W = 1000.0, w3 = 10.0; // kg of TNT, W^(1/3)
  std::map<std::string, double> worst;
  for (double z : {0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0, 30.0}) {
    const loads::BlastParameters b = kingery_bulmash(Burst::HemisphericalSurface, W, z * w3);
    REQUIRE(b.scaled_distance == Approx(z).epsilon(1e-12));
    const std::map<std::string, double> ours = {
        {"incident_overpressure", b.incident_pressure / 1e3},
        {"normal_reflected_overpressure", b.reflected_pressure / 1e3},
        {"incident_impulse", b.incident_impulse / w3},
        {"normal_reflected_impulse", b.reflected_impulse / w3},
        {"arrival_time", 1e3 * b.arrival_time / w3},
        {"positive_phase_duration", 1e3 * b.positive_duration / w3},
        {"shock_front_velocity", b.shock_speed / 1e3}};
    for (const auto& [q, v] : ours) worst[q] = std::max(worst[q], rel(v, swisdak_value(q, z)));
  }
  for (const auto& [q, e] : worst) std::printf("  %-30s largest difference %.2e\n", q.c_str(), e);
  // Two fits of the same trials by different authors (a mistyped coefficient shows as tens of
  // per cent); measured: incident pressure 0.71%, reflected 0.73%, impulses 0.32% and 0.01%,
  // arrival 0.25%, duration 0.96%, shock speed 0.53%.
  CHECK(worst["incident_overpressure"] < 0.01);
  CHECK(worst["normal_reflected_overpressure"] < 0.01);
  CHECK(worst["incident_impulse"] < 0.005);
  CHECK(worst["normal_reflected_impulse"] < 0.005);
  CHECK(worst["arrival_time"] < 0.005);
  CHECK(worst["positive_phase_duration"] < 0.0125);
  CHECK(worst["shock_front_velocity"] < 0.01);
}

TEST_CASE("Kingery-Bulmash free-air burst obeys the Rankine-Hugoniot relations of air", "[blast]") {
  // Ideal-gas shock in air at p0 = 101.325 kPa, c0 = 340.3 m/s, gamma = 1.4 (weak shocks,
  // Z >= 1.5, where real-gas effects are small): U = c0 sqrt(1 + 6 P_so / (7 p0)) and
  // P_r = 2 P_so (7 p0 + 4 P_so) / (7 p0 + P_so) (UFC 3-340-02 eqs. 2-3 and 2-4).
  const double p0 = 101.325e3, c0 = 340.3;
  for (Burst burst : {Burst::SphericalFreeAir, Burst::HemisphericalSurface})
    for (double z : {1.5, 2.0, 3.0, 5.0, 10.0, 20.0, 40.0}) {
      const loads::BlastParameters b = kingery_bulmash(burst, 1.0, z);
      const double pso = b.incident_pressure;
      INFO("Z = " << z);
      CHECK(rel(b.shock_speed, c0 * std::sqrt(1.0 + 6.0 * pso / (7.0 * p0))) < 0.01);
      CHECK(rel(b.reflected_pressure, 2.0 * pso * (7.0 * p0 + 4.0 * pso) / (7.0 * p0 + pso)) <
            0.02);
    }
}

TEST_CASE("Kingery-Bulmash parameters scale with the cube root of the charge", "[blast]") {
  for (Burst burst : {Burst::SphericalFreeAir, Burst::HemisphericalSurface}) {
    const loads::BlastParameters a = kingery_bulmash(burst, 1.0, 2.0);
    const loads::BlastParameters b = kingery_bulmash(burst, 8000.0, 40.0); // W^(1/3) = 20
    CHECK(b.incident_pressure == Approx(a.incident_pressure).epsilon(1e-12));
    CHECK(b.reflected_pressure == Approx(a.reflected_pressure).epsilon(1e-12));
    CHECK(b.shock_speed == Approx(a.shock_speed).epsilon(1e-12));
    CHECK(b.arrival_time == Approx(20.0 * a.arrival_time).epsilon(1e-12));
    CHECK(b.positive_duration == Approx(20.0 * a.positive_duration).epsilon(1e-12));
    CHECK(b.incident_impulse == Approx(20.0 * a.incident_impulse).epsilon(1e-12));
    // Pressure and impulse fall with distance; the shock arrives later.
    const loads::BlastParameters far = kingery_bulmash(burst, 1.0, 4.0);
    CHECK(far.incident_pressure < a.incident_pressure);
    CHECK(far.arrival_time > a.arrival_time);
  }
  // The surface burst is stronger than the free-air burst of the same charge (ground
  // reflection: about a 1.7-2x charge).
  CHECK(kingery_bulmash(Burst::HemisphericalSurface, 1.0, 3.0).incident_pressure >
        kingery_bulmash(Burst::SphericalFreeAir, 1.0, 3.0).incident_pressure);
  CHECK_THROWS_AS(kingery_bulmash(Burst::SphericalFreeAir, 1.0, 41.0), Error);
  CHECK_THROWS_AS(kingery_bulmash(Burst::HemisphericalSurface, 1.0, 0.05), Error);
  CHECK_THROWS_AS(kingery_bulmash(Burst::HemisphericalSurface, 0.0, 1.0), Error);
}

TEST_CASE("Friedlander pulse carries the fitted impulse", "[blast]") {
  for (double target : {0.05, 0.1, 0.2, 0.3, 0.45}) {
    loads::Friedlander f;
    f.arrival = 1e-3;
    f.duration = 4e-3;
    f.peak = 2e5;
    f.decay = loads::friedlander_decay(f.peak, f.duration, target * f.peak * f.duration);
    // Simpson's rule on the positive phase.
    const int n = 20000;
    const double h = f.duration / n;
    double s = f(f.arrival) + f(f.arrival + f.duration);
    for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f(f.arrival + k * h);
    const double integral = s * h / 3.0;
    INFO("I / (P t_d) = " << target << ", b = " << f.decay);
    CHECK(integral == Approx(target * f.peak * f.duration).epsilon(1e-8));
    CHECK(f.impulse() == Approx(integral).epsilon(1e-8));
    CHECK(f(f.arrival - 1e-9) == 0.0);
    CHECK(f(f.arrival) == Approx(f.peak));
  }
  CHECK(loads::friedlander_decay(1.0, 1.0, 0.6) == 0.0); // more than a triangle: b = 0
}

TEST_CASE("Blast pressure at an angle of incidence", "[blast]") {
  const loads::BlastParameters b = kingery_bulmash(Burst::HemisphericalSurface, 100.0, 10.0);
  const loads::Friedlander head_on = blast_pulse(b, 1.0), grazing = blast_pulse(b, 0.0),
                           behind = blast_pulse(b, -0.5);
  CHECK(head_on.peak == Approx(b.reflected_pressure));
  CHECK(head_on.impulse() == Approx(b.reflected_impulse).epsilon(1e-6));
  CHECK(grazing.peak == Approx(b.incident_pressure));
  CHECK(grazing.impulse() == Approx(b.incident_impulse).epsilon(1e-6));
  CHECK(behind.peak == Approx(b.incident_pressure));
  // Between the two: P_r c^2 + P_so (1 - c)^2, which dips below P_so near grazing incidence
  // (its minimum, P_r P_so / (P_r + P_so), is at c = P_so / (P_r + P_so)) and rises to P_r.
  CHECK(blast_pulse(b, 0.5).peak == Approx(0.25 * (b.reflected_pressure + b.incident_pressure)));
  const double c_min = b.incident_pressure / (b.reflected_pressure + b.incident_pressure);
  const double p_min =
      b.reflected_pressure * b.incident_pressure / (b.reflected_pressure + b.incident_pressure);
  CHECK(blast_pulse(b, c_min).peak == Approx(p_min));
  for (double c = 0.0; c <= 1.0; c += 0.05) CHECK(blast_pulse(b, c).peak >= p_min * (1 - 1e-12));
}
