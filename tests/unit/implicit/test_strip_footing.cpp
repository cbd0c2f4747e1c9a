// problems/strip_footing_prandtl.yaml, meshfree and 8-node quadrilaterals (reduced rule): the
// collapse pressure q of a smooth strip footing on a weightless Drucker-Prager soil (plane-strain
// match, associated flow) against Prandtl's c N_c, and the stresses of the two Rankine wedges of
// Prandtl's mechanism at collapse: under the footing (active) sigma_yy = -c N_c and sigma_xx =
// -(c N_c K_a - 2 c sqrt K_a), beside it under the free surface (passive) sigma_yy = 0 and
// sigma_xx = -2 c sqrt K_p, K_p = 1 / K_a = tan^2(45 deg + phi / 2) (Rankine's states with
// cohesion; Terzaghi 1943, ch. 2). The meshfree footing force is the further off (2-2.5%): the
// supports smear the settlement past the footing's corner, while the wedges are within 0.7%.
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

namespace {

double prandtl_nc(double phi) {
  const double nq = std::exp(M_PI * std::tan(phi)) * std::pow(std::tan(M_PI / 4 + phi / 2), 2);
  return (nq - 1.0) / std::tan(phi);
}

/// The mean stress [sxx, syy, sxy] of the Gauss points in the box [lo, hi].
Vec3 mean_stress(const implicit::ElastoplasticState& s, const Vec2& lo, const Vec2& hi) {
  const std::vector<Vec2> x = implicit::domain_rows(*s.model);
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if ((x[k].array() >= lo.array()).all() && (x[k].array() <= hi.array()).all()) {
      sum += s.stress[k];
      ++n;
    }
  REQUIRE(n > 10);
  return sum / n;
}

void check_footing(const std::string& method, double phi_degrees) {
  std::vector<std::string> set{"materials[0].plasticity.friction_angle=" +
                               std::to_string(phi_degrees)};
  if (method == "fem") set.push_back("discretisation.method=fem");
  const auto spec = load_problem("strip_footing_prandtl", set);
  const auto r = implicit::solve_elastoplastic_static(spec, test_session(), nullptr);
  REQUIRE(r.status == "completed");
  const double c = 1.0e4, phi = phi_degrees * M_PI / 180.0, half_width = 1.0;
  const auto& end = r.increments.back();
  REQUIRE(spec.galerkin().boundary[3].name == "footing");
  const double q = -end.boundary[3].force.y() / half_width;
  const double nc = prandtl_nc(phi);
  const double kp = std::pow(std::tan(M_PI / 4 + phi / 2), 2), ka = 1.0 / kp;
  // Around the centroid of each wedge: the active one under the footing, (0, 0), (1, 0) and
  // (0, -tan(45 deg + phi / 2)); the passive one beside it, (1, 0), (1 + 2 r1 cos a, 0) and
  // (1 + r1 cos a, -r1 sin a), a = 45 deg - phi / 2, r1 = exp(pi / 2 tan phi) / cos(45 deg +
  // phi / 2) the end radius of the log-spiral fan between them.
  const double a = M_PI / 4 - phi / 2, r1 = std::exp(M_PI / 2 * std::tan(phi)) / std::sin(a);
  const Vec2 ca(1.0 / 3.0, -std::tan(M_PI / 4 + phi / 2) / 3.0);
  const Vec2 cp(1.0 + r1 * std::cos(a), -r1 * std::sin(a) / 3.0);
  const Vec2 small(0.15, 0.1), large(0.3, 0.15); // the passive wedge is the larger
  const Vec3 active = mean_stress(r.state, ca - small, ca + small);
  const Vec3 passive = mean_stress(r.state, cp - large, cp + large);
  INFO(method << ", phi " << phi_degrees << ": q / c " << q / c << " against N_c " << nc
              << "\n  active wedge  " << active.transpose() / c << "\n  passive wedge "
              << passive.transpose() / c);
  CHECK(std::abs(q / (c * nc) - 1.0) < 0.03);
  // Each wedge's stress within 1% of its largest component: c N_c under the footing,
  // 2 c sqrt(K_p) beside it.
  const Vec3 active_exact(-(c * nc * ka - 2.0 * c * std::sqrt(ka)), -c * nc, 0.0);
  const Vec3 passive_exact(-2.0 * c * std::sqrt(kp), 0.0, 0.0);
  CHECK((active - active_exact).cwiseAbs().maxCoeff() < 0.01 * c * nc);
  CHECK((passive - passive_exact).cwiseAbs().maxCoeff() < 0.01 * -passive_exact(0));
}

} // namespace

TEST_CASE("a strip footing on a Drucker-Prager soil collapses at Prandtl's load, meshfree and Q8",
          "[elastoplastic][drucker_prager]") {
  for (const char* method : {"meshfree", "fem"}) check_footing(method, 20.0);
}

// Over the friction angles the meshfree footing, the further from N_c (+2.5% at 10 degrees,
// +2.1% at 30), is the one that can leave the 3%: Q8 is within 0.3% at all three angles
// (checked at 20 degrees above; its 10 and 30 degree runs, 40-50 s of the suite, were left out).
TEST_CASE("meshfree strip footings at friction angles 10 and 30 degrees collapse at Prandtl's load",
          "[elastoplastic][drucker_prager][long]") {
  for (double phi : {10.0, 30.0}) check_footing("meshfree", phi);
}
