// Input validation: each bad input is one error that names the key path.
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <catch2/catch.hpp>

using namespace mf;

namespace {
const char* kGood = R"(
name: t
analysis: elastic_static
model: {type: plane_stress, thickness: 1}
materials:
  - {name: steel, E: 2.0e5, nu: 0.3}
geometry:
  rectangle: {size: [2, 1]}
discretisation: {spacing: 0.25}
boundary:
  - {name: clamp, edges: left, displacement: {x: 0, y: 0}}
  - {name: pull, edges: right, traction: [1, 0]}
)";

std::string error_of(const std::string& assignment) {
  YAML::Node root = YAML::Load(kGood);
  try {
    if (!assignment.empty()) spec::apply_override(root, assignment);
    spec::parse_problem(root);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}
} // namespace

TEST_CASE("a valid problem parses with the documented defaults", "[input]") {
  const spec::ProblemSpec p = spec::parse_problem(YAML::Load(kGood));
  auto& galerkin = p.galerkin();
  CHECK(galerkin.discretisation.dilation.x() == 2.0);
  CHECK(galerkin.discretisation.order == 3);
  CHECK(galerkin.discretisation.cell_size == 0.25);
  CHECK(galerkin.boundary.size() == 2);
  CHECK(galerkin.boundary[0].penalty == Approx(1e6 * 2.0e5 / 0.25));
  CHECK(galerkin.boundary[0].mask == Vec2(1, 1));
  YAML::Node root = YAML::Load(kGood);
  spec::apply_override(root, "boundary.0.penalty_scale=1e3");
  CHECK(spec::parse_problem(root).galerkin().boundary[0].penalty == Approx(1e3 * 2.0e5 / 0.25));
  spec::apply_override(root, "boundary.0.penalty=1e12");
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::StartsWith("boundary[0].penalty_scale: give either"));
}

TEST_CASE("bad inputs are rejected with the key path and the value", "[input]") {
  CHECK(error_of("materials.0.E=-2e5") ==
        "materials[0].E: expected a positive number, got -200000");
  CHECK(error_of("materials.0.E=abc") == "materials[0].E: expected a number, got abc");
  CHECK(error_of("discretisation.spacing=0") ==
        "discretisation.spacing: expected a positive number, got 0");
  CHECK_THAT(error_of("discretisation.spcing=0.1"),
             Catch::StartsWith("discretisation.spcing: unknown key"));
  CHECK_THAT(error_of("discretisation.window=bspline"),
             Catch::Contains("discretisation.window: expected one of [cubic_spline, "
                             "quartic_spline, gaussian], got 'bspline'"));
  CHECK(error_of("boundary.0.edges=north") ==
        "boundary[0].edges: no boundary piece is named 'north' "
        "(the body's pieces: bottom, right, top, left; x_min, x_max, y_min and y_max name the "
        "edges on the sides of its bounding box)");
  CHECK(error_of("boundary.1.box=[[5, 5], [6, 6]]") ==
        "boundary[1]: selects no part of the boundary");
  CHECK(error_of("model.type=shell") == "model.type: expected one of [plane_stress, "
                                        "plane_strain, solid_3d, uniaxial_strain], got 'shell'");
  CHECK(error_of("geometry.rectangle.size=[1]") ==
        "geometry.rectangle.size: expected a pair [a, b], got [1]");
  CHECK_THAT(error_of("materials.0.nu=0.5"),
             Catch::StartsWith("materials[0].nu: expected a Poisson's ratio in (-1, 0.5)"));
  CHECK(error_of("boundary.0.displacement={}") ==
        "boundary[0].displacement: constrain at least one of x, y (or say 'exact')");
}

TEST_CASE("missing required values and missing constraints are errors", "[input]") {
  YAML::Node root = YAML::Load(kGood);
  root["materials"][0].remove("E");
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    "materials[0].E: analysis elastic_static needs Young's modulus E");
  YAML::Node free = YAML::Load(kGood);
  free["boundary"] = YAML::Load("[{name: pull, edges: right, traction: [1, 0]}]");
  CHECK_THROWS_WITH(spec::parse_problem(free),
                    Catch::Contains("boundary: no displacement condition"));
}

TEST_CASE("command-line overrides reach nested maps and list items", "[input]") {
  YAML::Node root = YAML::Load(kGood);
  spec::apply_override(root, "discretisation.spacing=0.125");
  spec::apply_override(root, "boundary.1.traction=[2, 0]");
  const spec::ProblemSpec p = spec::parse_problem(root);
  auto& galerkin = p.galerkin();
  CHECK(galerkin.discretisation.spacing == 0.125);
  CHECK(galerkin.boundary[1].traction == Vec2(2, 0));
  CHECK_THROWS_WITH(spec::apply_override(root, "boundary.7.name=x"),
                    Catch::Contains("index 7 is out of range"));
}

TEST_CASE("override paths in either style, a.1.b or a[1].b, and empty keys refused", "[input]") {
  YAML::Node root = YAML::Load(kGood);
  spec::apply_override(root, "boundary[1].traction=[3, 0]");
  CHECK(spec::parse_problem(root).galerkin().boundary[1].traction == Vec2(3, 0));
  for (const char* bad : {".name=x", "a..b=1", "boundary[]=1", "boundary[1]x=1", "name.=x"})
    CHECK_THROWS_WITH(spec::apply_override(root, bad),
                      Catch::Contains("an empty key") || Catch::Contains("expected"));
}

TEST_CASE("quoted text is one line: control characters escaped, cut at the limit", "[input]") {
  CHECK(spec::one_line(std::string("a\nb\tc\0d", 7)) == "a\\nb\\tc\\x00d");
  const std::string cut = spec::one_line(std::string(1000, 'x'));
  CHECK(cut.size() == 80);
  CHECK(cut.substr(77) == "...");
}

TEST_CASE("a polygon given clockwise runs as given counter-clockwise, its edges named in order",
          "[input]") {
  // The same 2 x 1 body listed both ways; edge_names[i] names the edge from vertex i to i + 1.
  YAML::Node ccw = YAML::Load(kGood), cw = YAML::Load(kGood);
  ccw["geometry"] = YAML::Load("{polygon: {vertices: [[0, 0], [2, 0], [2, 1], [0, 1]], "
                               "edge_names: [bottom, right, top, left]}}");
  cw["geometry"] = YAML::Load("{polygon: {vertices: [[0, 0], [0, 1], [2, 1], [2, 0]], "
                              "edge_names: [left, top, right, bottom]}}");
  const spec::ProblemSpec a = spec::parse_problem(ccw), b = spec::parse_problem(cw);
  for (std::size_t c = 0; c < a.galerkin().boundary.size(); ++c) {
    const auto length = [](const spec::ProblemSpec& p, std::size_t k) {
      double l = 0.0;
      Vec2 mid(0.0, 0.0);
      for (const auto& curve : spec::select_boundary(p.domain, p.galerkin().boundary[k].on, ""))
        l += curve.length(), mid += curve.length() * curve.point(0.5);
      return std::make_pair(l, Vec2(mid / l));
    };
    const auto [la, ma] = length(a, c);
    const auto [lb, mb] = length(b, c);
    CHECK(la == Approx(1.0)); // the left and right edges
    CHECK(lb == Approx(la));
    CHECK((mb - ma).norm() < 1e-12);
  }
  CHECK(b.domain.area_estimate() == Approx(2.0));
}

TEST_CASE("a Voce law that softens is refused unless the file says it means it", "[input]") {
  YAML::Node root = YAML::Load(kGood);
  root["analysis"] = "elastoplastic_static";
  root["materials"][0]["plasticity"] =
      YAML::Load("{yield_stress: 400, hardening: {type: voce, H: 0, sigma_inf: 300, delta: 10}}");
  root["steps"] = YAML::Load("[{name: pull, load_factor: 1, increments: 2}]");
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::Contains("materials[0].plasticity.hardening.sigma_inf: is below the "
                                    "yield stress 400: a softening law; give softening: true"));
  root["materials"][0]["plasticity"]["hardening"]["softening"] = "true";
  CHECK_NOTHROW(spec::parse_problem(root));
}

TEST_CASE("a hardening table that falls needs softening: true, and never ends falling", "[input]") {
  YAML::Node root = YAML::Load(kGood);
  root["analysis"] = "elastoplastic_static";
  root["steps"] = YAML::Load("[{name: pull, load_factor: 1, increments: 2}]");
  const auto with_points = [&](const std::string& points, const char* softening) {
    root["materials"][0]["plasticity"] = YAML::Load("{hardening: {type: table, points: " + points +
                                                    ", softening: " + softening + "}}");
  };
  const char* prefix = "materials[0].plasticity.hardening.points: ";
  with_points("[[0, 250], [0.01, 200], [0.1, 260]]", "false");
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::Contains(std::string(prefix) +
                                    "the yield stress falls from 250 to 200 at equivalent plastic "
                                    "strain 0.01: a softening law; give softening: true"));
  with_points("[[0, 250], [0.01, 200], [0.1, 260]]", "true");
  CHECK_NOTHROW(spec::parse_problem(root));
  // 300 at 0.005 to 100 at 0.01: on along that slope, zero at 0.01 + 100 / 40000.
  for (const char* softening : {"false", "true"}) {
    with_points("[[0, 300], [0.005, 300], [0.01, 100]]", softening);
    CHECK_THROWS_WITH(
        spec::parse_problem(root),
        Catch::Contains(std::string(prefix) + (softening[0] == 't' ? "the last segment falls"
                                                                   : "the yield stress falls")));
  }
  with_points("[[0, 300], [0.005, 300], [0.01, 100]]", "true");
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::Contains("(zero at equivalent plastic strain 0.0125)"));
  with_points("[[0, 300], [0.005, 300], [0.01, 100], [0.02, 100]]", "true");
  CHECK_NOTHROW(spec::parse_problem(root));
}

TEST_CASE("discretisation.adapt as a switch: off runs the file's cloud, on every default",
          "[input]") {
  auto adapt_of = [](const std::string& assignment) {
    YAML::Node root = YAML::Load(kGood);
    spec::apply_override(root, assignment);
    return spec::parse_problem(root).galerkin().discretisation.adapt;
  };
  for (const char* off : {"discretisation.adapt=off", "discretisation.adapt=false"})
    CHECK_FALSE(adapt_of(off).has_value());
  const spec::AdaptSpec defaults;
  for (const char* on : {"discretisation.adapt=on", "discretisation.adapt=true"}) {
    const auto a = adapt_of(on);
    REQUIRE(a.has_value());
    CHECK(a->target == defaults.target);
    CHECK(a->passes == defaults.passes);
  }
  CHECK(adapt_of("discretisation.adapt={target: 0.05}")->target == 0.05);
  CHECK(error_of("discretisation.adapt=sometimes") ==
        "discretisation.adapt: expected on, off or a map of keys, got sometimes");
  // until ends refinement during the analysis: without every there is none to end.
  CHECK(error_of("discretisation.adapt={target: 0.05, until: 1}") ==
        "discretisation.adapt.until: ends refinement during the analysis, which needs every: N "
        "(N > 0)");
  CHECK(error_of("discretisation.adapt={every: 1, until: 0}") ==
        "discretisation.adapt.until: expected an integer from 1 to 1000000, got 0");
  CHECK(error_of("discretisation.adapt={every: 1, until: 1.5}") ==
        "discretisation.adapt.until: expected an integer from 1 to 1000000, got 1.5");
  CHECK(error_of("discretisation.adapt={every: 5, until: 3}") ==
        "discretisation.adapt.until: is 3, before the first increment estimated (every: 5): no "
        "refinement would be made");
  CHECK_THAT(error_of("discretisation.adapt={every: 1, untill: 1}"),
             Catch::StartsWith("discretisation.adapt.untill: unknown key") &&
                 Catch::EndsWith("did you mean 'until'?"));
  // Off is allowed where adaptation is not: a finite-element run of a file that adapts.
  YAML::Node root = YAML::Load(kGood);
  spec::apply_override(root, "discretisation.method=fem");
  spec::apply_override(root, "discretisation.adapt=off");
  CHECK_NOTHROW(spec::parse_problem(root));
  spec::apply_override(root, "discretisation.adapt=on");
  CHECK_THROWS_WITH(spec::parse_problem(root),
                    Catch::StartsWith("discretisation.adapt: error-driven refinement places "
                                      "meshfree nodes"));
}
