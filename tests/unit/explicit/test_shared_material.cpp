// One `materials:` list, three analyses: the same steel entry is read by an elastoplastic
// Galerkin run, a peridynamics run and an SPH run, each taking its part of the material (and
// refusing clearly when that part is missing), and each run is checked against a closed form.
#include "meshfree/app/peridynamics.hpp"
#include "meshfree/app/sph_run.hpp"
#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/sph/step.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <variant>

using namespace mf;

namespace {

const double kE = 200e9, kNu = 0.3, kRho = 7850.0, kYield = 250e6;
const double kBulk = kE / (3.0 * (1.0 - 2.0 * kNu)), kShear = kE / (2.0 * (1.0 + kNu));

/// The shared part of every file: units and the one materials list.
const std::string kMaterials = R"(
units: N, m, kg, s
materials:
  - name: steel
    E: 200.0e9
    nu: 0.3
    density: 7850
    plasticity: {yield_stress: 250.0e6, hardening: perfect}
    eos: {type: linear_polynomial, rho0: 7850, c: [0, 166.66666666666666e9, 0, 0, 0, 0, 0]}
    bond: {law: pmb}
)";

/// A 1 x 2 bar in plane stress, stretched along y into the plastic range.
const std::string kBar = R"(
name: steel_bar
analysis: elastoplastic_static
model: {type: plane_stress, thickness: 1.0}
geometry: {rectangle: {origin: [0, 0], size: [1, 2]}}
discretisation: {spacing: 0.25}
boundary:
  - {name: left, edges: left, displacement: {x: 0}}
  - {name: bottom, edges: bottom, displacement: {y: 0}}
  - {name: top, edges: top, displacement: {y: 1}}
steps:
  - {name: elastic, load_factor: 1.0e-3, increments: 2}
  - {name: plastic, load_factor: 4.0e-3, increments: 5}
output:
  gauges: [{name: top_right, at: [1, 2]}, {name: bottom_right, at: [1, 0]}]
)";

/// A free 10 mm cube of particles moving as a rigid body.
const std::string kCube = R"(
name: steel_cube
analysis: peridynamics
model: {type: solid_3d}
geometry: {box: {origin: [0, 0, 0], size: [0.01, 0.01, 0.01]}}
discretisation: {spacing: 0.001, horizon: 3}
regions: [{velocity: [1, 0, 0]}]
time: {end: 2.0e-6}
output:
  gauges: [{name: centre, at: [0.005, 0.005, 0.005]}]
)";

/// Two steel bars meeting at x = 0 at +-5 m/s (uniaxial strain, below the elastic limit).
const std::string kImpact = R"(
name: steel_impact
analysis: sph
model: {type: uniaxial_strain}
discretisation: {smoothing: 1.5}
regions:
  - {material: steel, box: [[-0.02], [0.0]], spacing: 5.0e-5, energy: 0, velocity: [5.0]}
  - {material: steel, box: [[0.0], [0.02]], spacing: 5.0e-5, energy: 0, velocity: [-5.0]}
time: {end: 2.0e-6}
)";

spec::ProblemSpec parse(const std::string& analysis, const std::string& remove = "") {
  YAML::Node root = YAML::Load(kMaterials + analysis);
  if (!remove.empty()) root["materials"][0].remove(remove);
  return spec::parse_problem(root);
}

std::string error_of(const std::string& analysis, const std::string& remove) {
  try {
    parse(analysis, remove);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

} // namespace

TEST_CASE("one steel entry feeds an elastoplastic, a peridynamic and an SPH analysis",
          "[input][materials]") {
  const spec::ProblemSpec bar = parse(kBar), cube = parse(kCube), impact = parse(kImpact);
  // Galerkin: E, nu and the J2 law.
  CHECK(bar.elasticity().E == kE);
  CHECK(bar.elasticity().nu == kNu);
  REQUIRE(bar.plasticity());
  CHECK(std::get<materials::J2Parameters>(*bar.plasticity()).sigma0 == kYield);
  // Peridynamics: E, density and the bond.
  REQUIRE(cube.pd().materials.size() == 1);
  CHECK(cube.pd().materials[0].density == kRho);
  CHECK(cube.pd().materials[0].bond->critical_stretch == 0.0);
  // SPH: the equation of state, and a J2 solid with G = E / (2 (1 + nu)).
  REQUIRE(impact.sph().materials.size() == 1);
  CHECK(std::holds_alternative<materials::LinearPolynomial>(*impact.sph().materials[0].eos));
  CHECK(impact.sph().materials[0].shear_modulus == Approx(kShear).epsilon(1e-15));
  CHECK(impact.sph().regions[0].density == kRho);
}

TEST_CASE("each analysis names the part of the material it misses", "[input][materials]") {
  CHECK(error_of(kBar, "plasticity") ==
        "materials[0].plasticity: analysis elastoplastic_static needs a plasticity law");
  CHECK(error_of(kBar, "E") ==
        "materials[0].E: analysis elastoplastic_static needs Young's modulus E");
  CHECK_THAT(error_of(kCube, "bond"),
             Catch::StartsWith("materials[0].bond: analysis peridynamics needs bond parameters"));
  CHECK(error_of(kCube, "density") ==
        "materials[0].density: analysis peridynamics needs a density");
  CHECK(error_of(kImpact, "eos") == "materials[0].eos: analysis sph needs an equation of state");
}

TEST_CASE("shared steel, elastoplastic: a bar in uniaxial stress yields at sigma0",
          "[materials][elastoplastic]") {
  const spec::ProblemSpec spec = parse(kBar);
  const auto r = implicit::solve_elastoplastic_static(spec, test_session(), nullptr);
  REQUIRE(r.status == "completed");
  REQUIRE(r.increments.size() == 8); // the initial state and 2 + 5 increments
  // Uniaxial stress with perfect plasticity: sigma = min(E eps, sigma0) on a loading path; the
  // strain from the gauges (the penalty leaves the edges off their values by ~1e-7).
  double worst = 0.0;
  for (const auto& inc : r.increments) {
    const double strain = (inc.monitor_u.at(0).y() - inc.monitor_u.at(1).y()) / 2.0;
    const double sigma = std::min(kE * strain, kYield);
    worst = std::max(worst, std::abs(inc.boundary[2].force.y() - sigma * 1.0) / kYield);
  }
  CHECK(worst < 1e-6);
  CHECK(r.increments.back().boundary[2].force.y() == Approx(kYield).epsilon(1e-6));
}

TEST_CASE("shared steel, peridynamics: micromodulus from E and a free rigid translation",
          "[materials][pd]") {
  const spec::ProblemSpec spec = parse(kCube);
  PhaseTimer timer;
  const explicit_dynamics::PdSetup setup = explicit_dynamics::build_pd_setup(spec, timer);
  const double delta = 3.0 * 0.001;
  // Bond-based 3D solid: c = 12 E / (pi delta^4) (Silling & Askari 2005, k = 2E/3).
  REQUIRE(!setup.model.laws.empty());
  CHECK(setup.model.laws[0].c == Approx(12.0 * kE / (M_PI * std::pow(delta, 4))).epsilon(1e-14));
  const auto r = app::run_peridynamics(spec, nullptr);
  REQUIRE(r.status == "completed");
  for (const auto& [name, value] : r.gauge_maxima) {
    // Round-off in the bond stretches of the moving lattice is all that acts on the body.
    if (name == "centre_vx") CHECK(value == Approx(1.0).epsilon(1e-6));
    if (name == "centre_ux") CHECK(value == Approx(2.0e-6).epsilon(1e-6));
  }
}

TEST_CASE("shared steel, SPH: bulk sound speed and the stress behind an elastic front",
          "[materials][sph]") {
  const spec::ProblemSpec spec = parse(kImpact);
  sph::Hydro h = explicit_dynamics::build_sph(spec.sph());
  // A solid's sound speed at rest: the longitudinal c_L = sqrt((K + 4G/3) / rho), K from the
  // linear equation of state p = K mu and G from E and nu.
  const double cl = std::sqrt((kBulk + 4.0 / 3.0 * kShear) / kRho);
  CHECK(h.fields.c[0] == Approx(cl).epsilon(1e-12));
  const auto* vm = std::get_if<materials::VonMises>(&h.materials[0].strength);
  REQUIRE(vm);
  CHECK(vm->shear_modulus == Approx(kShear).epsilon(1e-15));
  const double t = spec.sph().end_time, v0 = 5.0;
  while (h.particles.time < t) sph::advance(h, std::min(sph::stable_step(h), t - h.particles.time));
  // Uniaxial strain: sigma_xx = -rho c_L v0 behind the fronts.
  const particles::ParticleSet& P = h.particles;
  const sph::ParticleFields& F = h.fields;
  double sum = 0.0;
  int count = 0;
  for (const int i : P.owned()) {
    const double x = P.position(i).x();
    if (x > 0.1 * cl * t && x < 0.8 * cl * t) sum += -F.p[i] + F.S[6 * i], ++count;
  }
  REQUIRE(count > 10);
  CHECK(sum / count == Approx(-kRho * cl * v0).epsilon(0.01));
}

TEST_CASE("stages: one stage runs as its analysis, and a later stage names where it starts from",
          "[input]") {
  YAML::Node root = YAML::Load(kMaterials + R"(
name: staged_bar
analysis: staged
geometry: {rectangle: {origin: [0, 0], size: [1, 2]}}
stages:
  - name: preload
    analysis: elastic_static
    model: {type: plane_stress}
    discretisation: {spacing: 0.25}
    boundary:
      - {name: bottom, edges: bottom, displacement: {x: 0, y: 0}}
)");
  root["materials"][0].remove("plasticity");
  const spec::ProblemSpec one = spec::parse_problem(root);
  CHECK(one.stage == "preload");
  CHECK(one.analysis == spec::Analysis::ElasticStatic);
  CHECK(one.name == "staged_bar");
  CHECK(one.galerkin().boundary.size() == 1);
  root["stages"].push_back(YAML::Load("{name: blast, analysis: sph}"));
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::StartsWith("stages[1].from: a later stage names the stage it starts "
                                      "from"));
  root["stages"][1]["from"] = "preload";
  root["stages"][1]["release"] = YAML::Load("[bottom]");
  CHECK_THROWS_WITH(spec::parse_problem(root), Catch::StartsWith("stages[1].model: required"));
  root["stages"].push_back(YAML::Load("{name: after, analysis: sph, from: blast}"));
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::StartsWith("stages: a staged run is a preload followed by one "
                                      "explicit stage"));
}
