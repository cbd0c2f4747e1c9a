// Unit-sanity warnings: plausible values in each common unit system pass silently; a value in
// the wrong units is named with its key and the range expected; no shipped problem warns.
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/spec/unit_sanity.hpp"
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

using namespace mf;

namespace {

/// A plane-stress plate of one material pulled by a traction, in the given units (elastoplastic
/// when the material has plasticity).
std::vector<std::string> warnings_of(const std::string& units, const std::string& material,
                                     const std::string& traction = "[1, 0]") {
  const bool plastic = material.find("plasticity") != std::string::npos;
  const std::string text =
      "name: t\nunits: " + units +
      "\nanalysis: " + (plastic ? "elastoplastic_static" : "elastic_static") +
      "\nmodel: {type: plane_stress}\n"
      "materials:\n  - {name: m, nu: 0.3, " +
      material +
      "}\ngeometry:\n  rectangle: {size: [2, 1]}\n"
      "discretisation: {spacing: 0.25}\nboundary:\n"
      "  - {name: clamp, edges: left, displacement: {x: 0, y: 0}}\n"
      "  - {name: pull, edges: right, traction: " +
      traction + "}\n" +
      (plastic ? "steps:\n  - {name: pull, load_factor: 1, increments: 1}\n" : "");
  return spec::unit_sanity_warnings(spec::parse_problem(YAML::Load(text)));
}

bool any_names(const std::vector<std::string>& lines, const std::string& key) {
  for (const auto& l : lines)
    if (l.find(key) != std::string::npos) return true;
  return false;
}

/// An SPH bar of aluminium in SI with the given spacing and end time.
std::vector<std::string> sph_warnings(const std::string& units, const std::string& end) {
  const std::string text =
      "name: t\nunits: " + units +
      "\nanalysis: sph\nmodel: {type: uniaxial_strain}\n"
      "materials:\n  - {name: al, shear_modulus: 26.0e9,\n"
      "     eos: {type: linear_polynomial, rho0: 2700, c: [0, 70.0e9, 0, 0, 0, 0, 0]}}\n"
      "regions:\n  - {material: al, box: [[0], [0.1]], spacing: 0.001, density: 2700, energy: 0}\n"
      "time: {end: " +
      end + "}\n";
  return spec::unit_sanity_warnings(spec::parse_problem(YAML::Load(text)));
}

} // namespace

TEST_CASE("unit systems are read from the units key", "[unit_sanity]") {
  const auto si = spec::parse_units("N, m, kg, s");
  REQUIRE(si);
  CHECK(si->stress() == 1.0);
  CHECK(si->density() == 1.0);
  const auto nmm = spec::parse_units("N, mm, MPa");
  REQUIRE(nmm);
  CHECK(nmm->stress() == Approx(1e6));
  CHECK(nmm->mass == Approx(1e3)); // N s^2 / mm: the tonne
  CHECK(nmm->density() == Approx(1e12));
  const auto kgf = spec::parse_units("kgf, mm, kgf/mm^2");
  REQUIRE(kgf);
  CHECK(kgf->stress() == Approx(9.80665e6));
  CHECK(spec::parse_units("N, mm, tonne, s")->density() == Approx(1e12));
  CHECK(spec::parse_units("N, mm, t, ms")->time == Approx(1e-3));
  CHECK_FALSE(spec::parse_units("consistent"));
  CHECK_FALSE(spec::parse_units("dimensionless"));
  CHECK_FALSE(spec::parse_units(""));
}

TEST_CASE("plausible values in each unit system give no warning", "[unit_sanity]") {
  struct Case {
    const char *units, *material, *traction;
  };
  const Case cases[] = {
      {"N, mm, tonne, s", "E: 2.1e5, density: 7.85e-9, plasticity: {yield_stress: 355}",
       "[100, 0]"},
      {"N, mm, MPa", "E: 2.1e5", "[100, 0]"},
      {"N, m, kg, s", "E: 2.1e11, density: 7850, plasticity: {yield_stress: 355.0e6}",
       "[1.0e8, 0]"},
      {"kgf, mm, kgf/mm^2", "E: 7000, plasticity: {yield_stress: 24.3}", "[10, 0]"},
      {"N, m, kg, s", "E: 1.0e6, density: 1100", "[1.0e3, 0]"},     // rubber
      {"consistent", "E: 2.1e11, density: 7.85e-9", "[1.0e20, 0]"}, // nothing to check
  };
  for (const Case& c : cases) {
    INFO(c.units << " / " << c.material << " / " << c.traction);
    const auto lines = warnings_of(c.units, c.material, c.traction);
    CAPTURE(lines);
    CHECK(lines.empty());
  }
}

TEST_CASE("values in the wrong units warn with the key and the range", "[unit_sanity]") {
  struct Case {
    const char *units, *material, *traction, *key;
  };
  const Case cases[] = {
      // E in Pa in an N-mm model: 2.1e17 Pa.
      {"N, mm, MPa", "E: 2.1e11", "[100, 0]", "materials[0].E = 2.1e+11"},
      // Density in kg/m^3 in an N-mm-tonne model: 7.85e15 kg/m^3.
      {"N, mm, tonne, s", "E: 2.1e5, density: 7850", "[100, 0]", "materials[0].density = 7.85e+03"},
      // ... whose wave speed is then 5 mm/s.
      {"N, mm, tonne, s", "E: 2.1e5, density: 7850", "[100, 0]", "wave speed"},
      // E in MPa in an SI model: 2.1e5 Pa is plausible for a foam, its wave speed with steel's
      // density (5 m/s) is not.
      {"N, m, kg, s", "E: 2.1e5, density: 7850", "[1, 0]", "wave speed"},
      // Yield stress in Pa, E in MPa.
      {"N, mm, MPa", "E: 2.1e5, plasticity: {yield_stress: 355.0e6}", "[100, 0]",
       "materials[0].plasticity.yield_stress = 3.55e+08"},
      {"N, mm, MPa", "E: 2.1e5, plasticity: {yield_stress: 355.0e6}", "[100, 0]", "of E ="},
      // A traction in Pa in an N-mm model: 1e14 Pa and a strain of 476.
      {"N, mm, MPa", "E: 2.1e5", "[1.0e8, 0]", "boundary[1].traction = 1e+08"},
      {"N, mm, MPa", "E: 2.1e5", "[1.0e8, 0]", "times the stiffest modulus"},
      // A mass unit that does not match force, length and time.
      {"N, mm, kg, s", "E: 2.1e5", "[100, 0]", "not a consistent set"},
      // A body 2 x 1 read in micrometres: 2e-6 m across.
      {"N, um, kg, s", "E: 2.1e5", "[1, 0]", "geometry: the body is 2 across, 2e-06 m"},
  };
  for (const Case& c : cases) {
    INFO(c.units << " / " << c.material << " / " << c.traction << " -> " << c.key);
    const auto lines = warnings_of(c.units, c.material, c.traction);
    CAPTURE(lines);
    CHECK(any_names(lines, c.key));
  }
  const auto lines = warnings_of("N, mm, MPa", "E: 2.1e11");
  REQUIRE(lines.size() == 1);
  CHECK(lines.front().find("usually lie within 1e+04..1e+13 Pa") != std::string::npos);
}

TEST_CASE("an explicit run's time step and step count are checked", "[unit_sanity]") {
  CHECK(sph_warnings("N, m, kg, s", "1.0e-4").empty());
  // A step of about 1e-3 / sqrt(26e9 / 2700) = 3.2e-7 s: an end time of 1e4 s is 3e10 steps.
  CHECK(any_names(sph_warnings("N, m, kg, s", "1.0e4"), "time.end = 1e+04"));
  // The same numbers read in mm: a 1 um spacing, moduli of 70 GPa x 1e6.
  CHECK(any_names(sph_warnings("N, mm, tonne, s", "1.0e-4"), "shear_modulus"));
  // A region 0.1 across: 1e-4 m in mm (the smallest body that passes), 1e-7 m in um.
  CHECK_FALSE(any_names(sph_warnings("N, mm, tonne, s", "1.0e-4"), "the body is"));
  CHECK(any_names(sph_warnings("N, um, kg, s", "1.0e-4"), "regions[0]: the body is 0.1 across"));
}

TEST_CASE("no shipped problem warns", "[unit_sanity]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(MESHFREE_SOURCE_DIR) / "problems";
  int read = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    INFO(entry.path().filename().string());
    const auto lines = spec::unit_sanity_warnings(spec::read_problem(entry.path().string()));
    CAPTURE(lines);
    CHECK(lines.empty());
    ++read;
  }
  CHECK(read >= 25); // the folder was found and read
}
