// What a staged analysis asks of the Galerkin side, against closed forms: a soil column under
// gravity with a geostatic (K0) initial stress and without one (uniaxial strain, K0 =
// nu / (1 - nu)), two materials in series, a uniform pressure on every boundary piece (curved
// ones included), and a point carried through the increments by point_law / update_point.
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/galerkin_forms.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>

using namespace mf;

namespace {

spec::ProblemSpec parse(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  YAML::Node root = YAML::Load(yaml);
  for (const auto& o : overrides) spec::apply_override(root, o);
  return spec::parse_problem(root);
}

std::string error_of(const std::string& yaml, const std::vector<std::string>& overrides) {
  try {
    parse(yaml, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const double kRho = 1800.0, kG = 9.81, kE = 50e6, kNu = 0.3, kH = 10.0;

/// A soil column 2 m wide and 10 m deep in plane strain: rollers on the sides, the base fixed
/// vertically, gravity, and the geostatic initial stress with K0 = 0.5.
const std::string kColumn = R"(
name: soil_column
units: N, m, kg, s
analysis: elastoplastic_static
model: {type: plane_strain}
materials:
  - {name: soil, E: 50.0e6, nu: 0.3, density: 1800}
geometry: {rectangle: {origin: [0, -10], size: [2, 10]}}
discretisation: {spacing: 0.5}
gravity: [0, -9.81]
initial_stress: {type: geostatic, surface: 0, k0: 0.5}
boundary:
  - {name: sides, edges: [left, right], displacement: {x: 0}}
  - {name: base, edges: bottom, displacement: {y: 0}}
)";

struct ColumnErrors {
  double syy = 0.0, ratio = 0.0; // largest relative errors below `depth`
  double syy_all = 0.0;          // largest |sigma_yy - exact| / (rho g H) over every point
  double u = 0.0;                // largest |u| / (rho g H^2 / E)
  double out_of_balance = 0.0;
  int iterations = 0;
};

/// The Gauss-point stresses of a converged column against sigma_yy = rho g y (y <= 0) and
/// sigma_xx = sigma_zz = k sigma_yy, relative at the points at least `depth` below the surface
/// (near it the stress tends to 0), and relative to rho g H everywhere.
ColumnErrors column_errors(const implicit::ElastoplasticResult& r, double k, double depth) {
  ColumnErrors e;
  const implicit::ElastoplasticState& st = r.state;
  const std::vector<Vec2> x = implicit::domain_rows(*st.model);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double syy = kRho * kG * x[i].y();
    e.syy_all = std::max(e.syy_all, std::abs(st.stress[i](1) - syy) / (kRho * kG * kH));
    if (-x[i].y() < depth) continue;
    e.syy = std::max(e.syy, std::abs(st.stress[i](1) - syy) / std::abs(syy));
    e.ratio = std::max(e.ratio, std::abs(st.stress[i](0) / st.stress[i](1) - k) / k);
    e.ratio = std::max(e.ratio, std::abs(st.stress_zz[i] / st.stress[i](1) - k) / k);
  }
  const implicit::ShapeTable t = implicit::shapes_at(*st.model, st.model->node_positions(), false);
  for (int n = 0; n < t.rows(); ++n)
    e.u = std::max(e.u, implicit::displacement_at(t, n, st.parameters).norm());
  e.u /= kRho * kG * kH * kH / kE;
  e.out_of_balance = r.initial_out_of_balance;
  e.iterations = r.increments.back().newton.iterations;
  return e;
}

} // namespace

TEST_CASE("a geostatic soil column is in equilibrium under gravity from the start",
          "[implicit][staging]") {
  // sigma0 balances gravity exactly (d sigma_yy / dy = rho g, sigma_xx constant along x) and is
  // traction-free at the surface, so the equilibrium step leaves it: the stress stays the
  // closed form and the displacement is what the penalty of the supports and the quadrature
  // leave. Q4 integrates the balance exactly; the rational RK functions do not, and the
  // out-of-balance of sigma0 is their quadrature error (measured: 7e-4 with 3 x 3 Gauss points
  // per cell, 7e-6 with 6 x 6, used here).
  for (const std::string method : {"fem", "meshfree"}) {
    const auto spec =
        parse(kColumn, {"discretisation.method=" + method, "discretisation.fem={element: q4}",
                        "discretisation.quadrature={order: 6}"});
    REQUIRE(spec.galerkin().steps.size() == 1);
    CHECK(spec.galerkin().steps[0].name == "geostatic");
    const auto r = implicit::solve_elastoplastic_static(spec, test_session(), nullptr);
    REQUIRE(r.status == "completed");
    CHECK(r.elastic_limit.skipped == "no material of the body has plasticity");
    const ColumnErrors e = column_errors(r, 0.5, 0.25);
    std::cout << "geostatic column, " << method << ": sigma_yy error " << e.syy << " (all points "
              << e.syy_all << " of rho g H), K0 error " << e.ratio << ", |u| / (rho g H^2 / E) "
              << e.u << ", out-of-balance " << e.out_of_balance << ", Newton iterations "
              << e.iterations << "\n";
    CHECK(e.syy < 0.01);
    CHECK(e.syy_all < 1e-3);
    CHECK(e.ratio < 0.01);
    CHECK(e.u < 1e-6);
    CHECK(e.out_of_balance < 1e-4);
    CHECK(e.iterations == 1);
  }
}

TEST_CASE("gravity turned on without an initial stress gives K0 = nu / (1 - nu)",
          "[implicit][staging]") {
  // Uniaxial strain under the column's weight: sigma_yy = rho g y, eps_xx = 0, so
  // sigma_xx = sigma_zz = nu / (1 - nu) sigma_yy. The exact u_y is quadratic in y, which Q8
  // elements and the quadratic RK basis contain; relative errors below the first row of Gauss
  // points (0.25 m), where the stress tends to 0 at the surface.
  for (const std::string basis : {"fem", "quadratic"}) {
    YAML::Node root = YAML::Load(kColumn);
    root.remove("initial_stress");
    spec::apply_override(root, "steps=[{name: gravity, factors: {body_force: 1}, increments: 1}]");
    spec::apply_override(root, basis == "fem" ? "discretisation.method=fem"
                                              : "discretisation.basis=quadratic");
    const spec::ProblemSpec spec = spec::parse_problem(root);
    const auto r = implicit::solve_elastoplastic_static(spec, test_session(), nullptr);
    REQUIRE(r.status == "completed");
    const ColumnErrors e = column_errors(r, kNu / (1.0 - kNu), 0.25);
    std::cout << "gravity turn-on, " << basis << ": sigma_yy error " << e.syy << " (all points "
              << e.syy_all << " of rho g H), ratio error " << e.ratio << "\n";
    CHECK(e.syy < 0.01);
    CHECK(e.syy_all < 0.01);
    CHECK(e.ratio < 0.01);
  }
  // elastic_static takes gravity through the same body force: Q8 nodal stresses.
  YAML::Node root = YAML::Load(kColumn);
  root.remove("initial_stress");
  spec::apply_override(root, "analysis=elastic_static");
  spec::apply_override(root, "discretisation.method=fem");
  const auto r = implicit::solve_elastic_static(spec::parse_problem(root), test_session());
  double worst = 0.0;
  for (std::size_t n = 0; n < r.node_x.size(); ++n) {
    if (-r.node_x[n].y() < 0.25) continue;
    const double syy = kRho * kG * r.node_x[n].y();
    worst = std::max({worst, std::abs(r.node_stress[n](1) - syy) / std::abs(syy),
                      std::abs(r.node_stress[n](0) / syy - kNu / (1.0 - kNu))});
  }
  std::cout << "gravity turn-on, elastic_static Q8 nodes: largest error " << worst << "\n";
  if (test_session().rank() == 0) CHECK(worst < 1e-6);
}

namespace {

/// A bar 2 x 0.5 in plane stress, pulled by an end traction t = 1: soft (E 100, nu 0.2) for
/// x < 1, stiff (E 200, nu 0.4) beyond. With nu / E the same in both, the lateral strain
/// -nu t / E is the same and the exact field is uniaxial stress sigma_xx = t:
/// u_x = t x / E1 (x <= 1), t / E1 + t (x - 1) / E2 (x >= 1); u_y = -nu1 t y / E1.
const std::string kBimaterialBar = R"(
name: bimaterial_bar
units: consistent
analysis: elastic_static
model: {type: plane_stress}
materials:
  - {name: soft, E: 100.0, nu: 0.2}
  - {name: stiff, E: 200.0, nu: 0.4}
material: soft
material_regions: [{material: stiff, box: [[1, -1], [3, 2]]}]
geometry: {rectangle: {origin: [0, 0], size: [2, 0.5]}}
discretisation: {spacing: 0.1}
boundary:
  - {name: left, edges: left, displacement: {x: 0}}
  - {name: bottom, edges: bottom, displacement: {y: 0}}
  - {name: pull, edges: right, traction: [1.0, 0]}
)";

Vec2 bimaterial_exact(const Vec2& x) {
  const double ux = x.x() <= 1.0 ? x.x() / 100.0 : 1.0 / 100.0 + (x.x() - 1.0) / 200.0;
  return {ux, -0.2 / 100.0 * x.y()};
}

/// Largest |u^h - u| at the nodes relative to the largest |u|, and the left reaction.
std::pair<double, double> bimaterial_error(const std::vector<std::string>& overrides) {
  const auto spec = parse(kBimaterialBar, overrides);
  const auto r = implicit::solve_elastic_static(spec, test_session());
  double worst = 0.0, largest = 0.0;
  for (std::size_t n = 0; n < r.node_x.size(); ++n) {
    worst = std::max(worst, (r.node_u[n] - bimaterial_exact(r.node_x[n])).norm());
    largest = std::max(largest, bimaterial_exact(r.node_x[n]).norm());
  }
  return {largest > 0.0 ? worst / largest : 0.0, r.boundary.at(0).force.x()};
}

} // namespace

TEST_CASE("two materials in series carry one stress with a kink in the displacement",
          "[implicit][staging]") {
  // Q4 elements with a node line on the interface contain the piecewise-linear field: what is
  // left is the penalty's (about 1e-7 of the displacement). The RK functions are smooth across
  // the interface and spread the kink over a support (2 h): an O(h) error near it (measured
  // 4.4e-3 of max |u| at h = 0.1, 2.3e-3 at h = 0.05).
  const auto [fe, fe_reaction] =
      bimaterial_error({"discretisation.method=fem", "discretisation.fem={element: q4}"});
  const auto [rk, rk_reaction] = bimaterial_error({});
  const auto [rk_fine, rk_fine_reaction] = bimaterial_error({"discretisation.spacing=0.05"});
  std::cout << "bimaterial bar: largest nodal error relative to max |u|: FE Q4 " << fe << ", RK h "
            << "0.1 " << rk << ", h 0.05 " << rk_fine << "; reactions " << fe_reaction << ", "
            << rk_reaction << " (exact -0.5)\n";
  CHECK(fe < 1e-6);
  CHECK(rk < 5e-3);
  if (test_session().rank() == 0) CHECK(rk_fine < 0.7 * rk); // node fields live on rank 0
  CHECK(std::abs(fe_reaction + 0.5) < 1e-6);
  CHECK(std::abs(rk_reaction + 0.5) < 1e-6);
}

namespace {

const std::string kPressurePatch = R"(
name: pressure_patch
units: consistent
analysis: elastic_static
model: {type: plane_strain}
materials: [{name: m, E: 1000.0, nu: 0.25}]
geometry:
  rectangle: {origin: [0, 0], size: [2, 2]}
  holes: [{center: [0, 0], radius: 0.5, name: hole}]
discretisation: {spacing: 0.1}
boundary:
  - {name: symmetry_x, edges: left, displacement: {x: 0}}
  - {name: symmetry_y, edges: bottom, displacement: {y: 0}}
  - {name: outer, edges: [right, top], pressure: 2.0}
  - {name: inner, edges: hole, pressure: 2.0}
)";

} // namespace

TEST_CASE("a uniform pressure on every boundary piece, the hole's arc included, is hydrostatic",
          "[implicit][staging]") {
  // The quarter of a plate with a hole, symmetry rollers on the cut edges, pressure p on the
  // outer edges and in the hole: sigma = -p I in the plane whatever the shape (t = -p n on
  // every piece), so u = eps x with eps = -p (1 + nu)(1 - 2 nu) / E in plane strain. A linear
  // field: the RK patch test, to the quadrature error of the cut cells.
  const double p = 2.0, E = 1000.0, nu = 0.25;
  const auto spec = parse(kPressurePatch);
  REQUIRE(spec.galerkin().boundary[3].pressure_load);
  const auto r = implicit::solve_elastic_static(spec, test_session());
  const double eps = -p * (1.0 + nu) * (1.0 - 2.0 * nu) / E;
  double u_err = 0.0, s_err = 0.0;
  for (std::size_t n = 0; n < r.node_x.size(); ++n) {
    u_err = std::max(u_err, (r.node_u[n] - eps * r.node_x[n]).norm() / (std::abs(eps) * 2.0));
    s_err = std::max(s_err, (r.node_stress[n] - Vec3(-p, -p, 0.0)).cwiseAbs().maxCoeff() / p);
  }
  // The loads on the outer edges: -p times their length (2 each, the hole cuts nothing of
  // them); on the hole's quarter arc: p a (1, 1), away from the hole's centre, into the body.
  // Nodal stresses are derivatives of the RK functions: the largest error (measured 1.4e-2)
  // is at the nodes on the arc, the cut cells' quadrature error of the patch test.
  const Vec2 outer = r.boundary[2].force, inner = r.boundary[3].force;
  std::cout << "pressure patch: nodal displacement error " << u_err << ", stress error " << s_err
            << ", loads " << outer.transpose() << " | " << inner.transpose() << "\n";
  CHECK(std::abs(outer.x() + p * 2.0) < 1e-9);
  CHECK(std::abs(outer.y() + p * 2.0) < 1e-9);
  CHECK(std::abs(inner.x() - p * 0.5) < 1e-6);
  CHECK(std::abs(inner.y() - p * 0.5) < 1e-6);
  CHECK(u_err < 1e-3);
  CHECK(s_err < 2e-2);

  // Finite elements take the outward normals of their boundary edges: the rectangle without
  // the hole under the same pressure, a field Q4 elements contain (the penalty's error left).
  YAML::Node root = YAML::Load(kPressurePatch);
  root["geometry"].remove("holes");
  root["boundary"].remove(3);
  spec::apply_override(root, "discretisation.method=fem");
  spec::apply_override(root, "discretisation.fem={element: q4}");
  const auto fe = implicit::solve_elastic_static(spec::parse_problem(root), test_session());
  double fe_err = 0.0;
  for (std::size_t n = 0; n < fe.node_x.size(); ++n)
    fe_err = std::max({fe_err, (fe.node_u[n] - eps * fe.node_x[n]).norm() / (std::abs(eps) * 2.0),
                       (fe.node_stress[n] - Vec3(-p, -p, 0.0)).cwiseAbs().maxCoeff() / p});
  std::cout << "pressure patch, FE Q4 without the hole: largest error " << fe_err << "\n";
  CHECK(fe_err < 1e-6);
}

namespace {

/// Two layers under gravity from a geostatic start: an elastic crust (3 m) on sand with J2 and
/// linear hardening whose yield stress the geostatic deviator (1 - K0) |sigma_v| exceeds below
/// about 6.5 m, then a surcharge pressure on the surface.
const std::string kLayers = R"(
name: layered_column
units: N, m, kg, s
analysis: elastoplastic_static
model: {type: plane_strain}
materials:
  - name: sand
    E: 50.0e6
    nu: 0.3
    density: 1800
    plasticity: {yield_stress: 60.0e3, hardening: {type: linear, H: 5.0e6}}
  - {name: crust, E: 80.0e6, nu: 0.25, density: 2000}
material: sand
material_regions: [{material: crust, box: [[-1, -3], [3, 1]]}]
geometry: {rectangle: {origin: [0, -10], size: [2, 10]}}
discretisation: {spacing: 0.5}
gravity: [0, -9.81]
initial_stress: {type: geostatic, surface: 0, k0: 0.5}
boundary:
  - {name: sides, edges: [left, right], displacement: {x: 0}}
  - {name: base, edges: bottom, displacement: {y: 0}}
  - {name: surcharge, edges: top, pressure: 50.0e3}
steps: [{name: load, load_factor: 1, increments: 3}]
)";

} // namespace

TEST_CASE("the geostatic stress is the weight of the column above, layer by layer",
          "[implicit][staging]") {
  // sigma_v = -g sum rho_i t_i over the layers above; a hole in the column carries no weight.
  spec::ProblemSpec spec = parse(kLayers);
  const double g = 9.81;
  CHECK(implicit::material_at(spec, {1.0, -1.0}) == 1);
  CHECK(implicit::material_at(spec, {1.0, -5.0}) == 0);
  const Vec4 s = implicit::initial_stress_at(spec, {0.3, -7.0});
  const double sv = -g * (2000.0 * 3.0 + 1800.0 * 4.0);
  CHECK(std::abs(s(1) - sv) <= 1e-12 * std::abs(sv));
  CHECK(std::abs(s(0) - 0.5 * sv) <= 1e-12 * std::abs(sv));
  CHECK(std::abs(s(3) - 0.5 * sv) <= 1e-12 * std::abs(sv));
  CHECK(s(2) == 0.0);
  spec.domain.add_hole({Vec2(1.0, -5.0), 1.0, "cavity"});
  const Vec4 below = implicit::initial_stress_at(spec, {1.0, -7.0}); // the hole spans -6..-4
  const double sv_hole = -g * (2000.0 * 3.0 + 1800.0 * 2.0);
  CHECK(std::abs(below(1) - sv_hole) <= 1e-12 * std::abs(sv_hole));
  const double dx = 0.6, half = std::sqrt(1.0 - dx * dx); // a column through the hole's side
  const Vec4 side = implicit::initial_stress_at(spec, {1.0 + dx, -7.0});
  const double sv_side = -g * (2000.0 * 3.0 + 1800.0 * (4.0 - 2.0 * half));
  CHECK(std::abs(side(1) - sv_side) <= 1e-12 * std::abs(sv_side));
  CHECK(implicit::initial_stress_at(spec, {1.0, 0.5}).isZero());
}

TEST_CASE("a point carried through the increments by update_point has the Gauss point's state",
          "[implicit][staging]") {
  // The layered column: geostatic start (the deep sand yields in the equilibrium step), then a
  // surcharge. Each Gauss point, carried as a passive material point through the recorded
  // increments with point_law / update_point and the strain of each increment's parameters,
  // ends in the state the solver committed there: the same numbers with the meshfree shape
  // functions (evaluated by the same code), to round-off with finite elements (whose shapes_at
  // maps the point back into its element).
  for (const std::string method : {"meshfree", "fem"}) {
    spec::ProblemSpec spec = parse(kLayers, {"discretisation.method=" + method});
    spec.galerkin().record_increment_parameters = true;
    REQUIRE(spec.galerkin().steps.size() == 2);
    const auto r = implicit::solve_elastoplastic_static(spec, test_session(), nullptr);
    REQUIRE(r.status == "completed");
    CHECK(r.elastic_limit.skipped ==
          "the body starts from an initial stress, so the stresses do not scale with the load");
    REQUIRE(r.increments.size() == 5);
    for (const auto& inc : r.increments)
      REQUIRE(inc.parameters.size() == r.state.parameters.size());
    for (double v : r.increments.front().parameters) REQUIRE(v == 0.0);
    CHECK(r.increments.back().parameters == r.state.parameters);
    CHECK(r.increments[1].plastic_points > 0);
    const implicit::GalerkinModel& m = *r.state.model;
    const std::vector<Vec2> x = implicit::domain_rows(m);
    const implicit::ShapeTable carried = implicit::shapes_at(m, x, true);
    double worst = 0.0, scale = 0.0, worst_plastic = 0.0;
    long plastic = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      const implicit::PointLaw law = implicit::point_law(spec, x[k]);
      materials::MaterialState state;
      materials::StressUpdate2D res;
      for (std::size_t i = 1; i < r.increments.size(); ++i) {
        const Vec3 eps =
            implicit::strain_at(carried, static_cast<int>(k), r.increments[i].parameters);
        res = implicit::update_point(spec, law, eps, state);
        state = res.state;
      }
      plastic += res.plastic;
      scale = std::max(scale, r.state.stress[k].cwiseAbs().maxCoeff());
      worst = std::max({worst, (res.stress - r.state.stress[k]).cwiseAbs().maxCoeff(),
                        std::abs(res.stress_zz - r.state.stress_zz[k])});
      worst_plastic = std::max(
          {worst_plastic, std::abs(state.alpha - r.state.history[k].alpha),
           (state.plastic_strain - r.state.history[k].plastic_strain).cwiseAbs().maxCoeff()});
    }
    std::cout << "carried points, " << method << ": " << x.size() << ", plastic at the end "
              << plastic << ", largest stress difference " << worst / scale
              << " of the largest stress, of plastic strain " << worst_plastic
              << "; geostatic step: " << r.increments[1].newton.iterations
              << " Newton iterations, out-of-balance " << r.initial_out_of_balance << "\n";
    CHECK(plastic > 0);
    CHECK(worst <= 1e-12 * scale);
    CHECK(worst_plastic <= 1e-12);
  }
}

TEST_CASE("the staging inputs name the key of what is wrong", "[implicit][staging][input]") {
  CHECK(error_of(kLayers, {"material_regions.0.material=clay"}) ==
        "material_regions[0].material: no material is named 'clay' (materials: sand, crust)");
  CHECK(error_of(kLayers, {"materials.1={name: crust, E: 80.0e6, nu: 0.25}"}) ==
        "materials[1].density: gravity needs the density of every material of the body");
  CHECK(error_of(kLayers, {"gravity=[0, 0]"})
            .find("initial_stress: a geostatic initial stress "
                  "needs 'gravity'") == 0);
  CHECK(error_of(kLayers, {"gravity=[0, 9.81]"})
            .find("gravity: a geostatic initial stress needs "
                  "gravity along -y") == 0);
  CHECK(error_of(kLayers, {"initial_stress.k0=-1"}) ==
        "initial_stress.k0: expected a number >= 0, got -1");
  CHECK(error_of(kLayers, {"material_regions.0={material: crust}"})
            .find("material_regions[0].material: give the region") == 0);
  CHECK(error_of(kLayers, {"boundary.2.traction=[0, 1]"}) ==
        "boundary[2].pressure: give one of 'displacement', 'traction' or 'pressure'");
  CHECK(error_of(kLayers, {"steps.0.name=geostatic"}) ==
        "steps[0].name: another step is named 'geostatic'");
  CHECK(error_of(kBimaterialBar, {"initial_stress={type: geostatic, surface: 0, k0: 0.5}"})
            .find("initial_stress: used only by analysis elastoplastic_static") == 0);
}
