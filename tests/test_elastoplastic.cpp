// Elastoplastic analysis through the whole solver: a homogeneous bar against the closed-form
// uniaxial response (load, unload, reverse yielding), quadratic convergence of Newton with the
// consistent tangent, and the load schedule's bookkeeping.
#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>

using namespace mf;

namespace {

/// One-dimensional J2 response (uniaxial stress) with isotropic hardening sigma_y(alpha) and
/// linear kinematic hardening Hk: backward Euler on |sigma - b| - sigma_y(alpha) <= 0, written
/// independently of the 3D return mapping under test.
struct Uniaxial {
  materials::J2Parameters p;
  double plastic = 0.0, back = 0.0, alpha = 0.0;

  double stress(double strain) {
    const double trial = p.E * (strain - plastic);
    const double xi = trial - back;
    if (std::abs(xi) <= materials::yield_stress(p, alpha)) return trial;
    const double sign = xi > 0.0 ? 1.0 : -1.0;
    double dl = 0.0;
    for (int it = 0; it < 100; ++it) {
      const double g =
          std::abs(xi) - (p.E + p.H_kinematic) * dl - materials::yield_stress(p, alpha + dl);
      const double dg = -(p.E + p.H_kinematic) - materials::yield_slope(p, alpha + dl);
      dl -= g / dg;
      if (std::abs(g) < 1e-12 * p.sigma0) break;
    }
    plastic += sign * dl;
    back += sign * p.H_kinematic * dl;
    alpha += dl;
    return trial - sign * p.E * dl;
  }
};

/// Largest |reaction - sigma_exact * area| over the increments, relative to the largest stress.
double bar_error(const std::vector<std::string>& overrides) {
  const auto spec = load_problem("bar_uniaxial_cyclic", overrides);
  const auto r = app::solve_elastoplastic_static(spec, test_session(), nullptr);
  REQUIRE(r.status == "completed");
  Uniaxial exact{*spec.plasticity};
  const double length = 2.0, area = 1.0; // height and width x thickness of the bar
  double worst = 0.0, largest = 0.0;
  int top = -1;
  for (std::size_t c = 0; c < spec.boundary.size(); ++c)
    if (spec.boundary[c].name == "top") top = static_cast<int>(c);
  REQUIRE(top >= 0);
  for (const auto& inc : r.increments) {
    // The strain the body really has: the penalty leaves the top and bottom edges off their
    // prescribed values by about 1e-7 of the stretch, which is the penalty's error, not the
    // material's.
    const double stretch = inc.monitor_u.at(0).y() - inc.monitor_u.at(1).y();
    const double sigma = exact.stress(stretch / length);
    worst = std::max(worst, std::abs(inc.boundary[top].force.y() - sigma * area));
    largest = std::max(largest, std::abs(sigma));
  }
  REQUIRE(r.increments.size() == 41);
  return worst / largest;
}

} // namespace

TEST_CASE("a bar in uniaxial stress follows the closed-form cyclic response", "[elastoplastic]") {
  // The exact field is linear, which both discretisations contain; finite elements integrate
  // it exactly (round-off, amplified by the penalty, is left), the rational RK functions up to
  // the quadrature error of the patch test.
  const double fe_q4 = bar_error({"discretisation.method=fem", "discretisation.fem.element=q4"});
  const double fe_q8 = bar_error({"discretisation.method=fem"});
  const double meshfree = bar_error({});
  std::cout << "bar: largest reaction error relative to the largest stress: meshfree " << meshfree
            << ", FE Q4 " << fe_q4 << ", FE Q8 " << fe_q8 << "\n";
  // Measured: FE 8e-9 and 1.1e-8 (the Newton tolerance, 1e-8 of the force scale), meshfree 6e-8.
  CHECK(fe_q4 < 1e-7);
  CHECK(fe_q8 < 1e-7);
  CHECK(meshfree < 1e-6);
}
