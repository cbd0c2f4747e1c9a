#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/step.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <limits>
#include <yaml-cpp/yaml.h>

using namespace mf;

namespace {
/// Two blocks of gas at rest in a plane, expanding into vacuum: the default bounds and a region
/// that gives its own, at another density.
const char* const kTwoBlocks = R"(
name: bounds
units: dimensionless
analysis: sph
model: {type: plane_strain}
discretisation: {smoothing: 1.5}
materials:
  - {name: gas, eos: {type: ideal_gas, gamma: 1.4}}
regions:
  - {material: gas, box: [[0, 0], [0.2, 0.2]], spacing: 0.01, density: 1.0, pressure: 1.0}
  - {material: gas, box: [[0.6, 0], [0.7, 0.1]], spacing: 0.01, density: 2.0, pressure: 1.0,
     smoothing_bounds: [0.5, 1.5]}
time: {end: 0.1}
)";
} // namespace

TEST_CASE("SPH smoothing bounds: the 2D default, a region's own, and gas expanding into vacuum "
          "held at them",
          "[sph]") {
  const spec::ProblemSpec spec = spec::parse_problem(YAML::Load(kTwoBlocks));
  const spec::SphSpec& s = spec.sph();
  CHECK(s.smoothing_bounds.min == 0.2); // LS-DYNA's HMIN and HMAX in 2D and 3D
  CHECK(s.smoothing_bounds.max == 2.0);
  CHECK(s.regions[0].smoothing_bounds.max == 2.0);
  CHECK(s.regions[1].smoothing_bounds.min == 0.5);
  CHECK(s.regions[1].smoothing_bounds.max == 1.5);
  for (const bool bounded : {true, false}) {
    sph::Hydro h = explicit_dynamics::build_sph(s);
    const sph::ParticleFields& F = h.fields;
    const particles::ParticleSet& P = h.particles;
    // The density bounds that keep h = h0 (rho0 / rho)^(1/2) within [min, max] h0.
    for (int i = 0; i < P.size(); ++i) {
      const bool second = P.X[3 * i] > 0.5;
      const double rho0 = second ? 2.0 : 1.0, lo = second ? 0.5 : 0.2, hi = second ? 1.5 : 2.0;
      REQUIRE(F.rho_lo[i] == Approx(rho0 / (hi * hi)).epsilon(1e-15));
      REQUIRE(F.rho_hi[i] == Approx(rho0 / (lo * lo)).epsilon(1e-15));
    }
    if (!bounded)
      for (int i = 0; i < P.size(); ++i)
        h.fields.rho_lo[i] = 0.0, h.fields.rho_hi[i] = std::numeric_limits<double>::infinity();
    double largest[2] = {0.0, 0.0}; // h / h0 in each block, over every step
    while (h.particles.time < s.end_time) {
      sph::advance(h, std::min(sph::stable_step(h), s.end_time - h.particles.time));
      for (int i = 0; i < P.size(); ++i) {
        double& l = largest[P.X[3 * i] > 0.5 ? 1 : 0];
        l = std::max(l, F.h[i] / F.h_ref[i]);
      }
    }
    std::printf("  gas blocks expanding into vacuum, %s: largest h / h0 %.4g and %.4g, held at the "
                "largest %ld particle-steps, %ld steps\n",
                bounded ? "bounded" : "unbounded", largest[0], largest[1], h.bounded_h.at_max,
                h.particles.step);
    INFO((bounded ? "bounded" : "unbounded"));
    if (bounded) {
      CHECK(largest[0] <= 2.0 * (1 + 1e-12));
      CHECK(largest[1] <= 1.5 * (1 + 1e-12));
      CHECK(h.bounded_h.at_max > 0);
      CHECK(h.bounded_h.at_min == 0);
    } else { // the bounds are what held them
      CHECK(largest[0] > 2.0);
      CHECK(largest[1] > 1.5);
    }
  }
}
