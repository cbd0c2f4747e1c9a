// The LPS passes' packed rows (AVX2) against their scalar rows: the same forces, energy densities,
// dilatations, broken bonds and s0 bit for bit, through breaking, in both layouts, on one and two
// threads, with and without the position-aware influence.
#include "meshfree/core/simd_target.hpp"
#include "meshfree/pd/state_based.hpp"
#include "meshfree/pd/state_surface.hpp"
#include "pd/lps_body.hpp"
#include <catch2/catch.hpp>
#include <iostream>
#include <omp.h>

using namespace mf;
using materials::PdDimension;
using namespace mf::test; // lps_lattice, deformed, Elastic

namespace {

struct Evaluation {
  std::vector<std::vector<double>> force, density, theta;
  std::vector<long> broken;
  std::vector<unsigned char> intact;
  std::vector<double> s0;
};

/// Three evaluations of growing deformation (bonds break in the second and third) under `target`.
Evaluation evaluate(PdDimension dim, bool full, bool aware, bool alpha, int threads,
                    SimdTarget target) {
  const bool plane = dim != PdDimension::Solid3D;
  pd::Model m = lps_lattice(dim, 9, 7, 6, 1e-3, plane ? 3.5 : 3.0, Elastic{70e9, 0.3}, 2700.0,
                            pd::VolumeCorrection::Exact, materials::Influence::InverseLength, full);
  m.laws[0].critical_stretch = 1.5e-3;
  m.laws[0].alpha = alpha ? 0.25 : 0.0;
  pd::fold_laws(m);
  pd::BondState s = pd::initial_state(m, {});
  if (aware) REQUIRE(pd::apply_position_aware_influence(m, s) == 0);
  set_simd_target(target);
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Evaluation e;
  for (int pass = 0; pass < 3; ++pass) {
    const double a = (1.0 + pass) * 0.5e-4; // largest strain 0.8e-3, 1.6e-3, 2.4e-3
    const std::vector<double> y = deformed(m, [a](const Eigen::Vector3d& x) {
      return Eigen::Vector3d(a * x.x() * x.x() / 1e-3, 0.3 * a * x.x() * x.y() / 1e-3,
                             -0.2 * a * x.z() * x.y() / 1e-3);
    });
    std::vector<double> f, w, theta;
    e.broken.push_back(pd::state_forces(m, s, y, f, true, &w, &theta).broken);
    e.force.push_back(f), e.density.push_back(w), e.theta.push_back(theta);
  }
  omp_set_num_threads(before);
  set_simd_target(preferred_simd_target());
  e.intact = s.intact;
  e.s0 = s.s0.committed;
  return e;
}

} // namespace

TEST_CASE("LPS: the packed rows give the scalar rows' numbers bit for bit", "[pd][lps][simd]") {
  const std::vector<SimdTarget> targets = simd_targets();
  if (targets.size() < 2) {
    WARN("this processor runs the scalar rows only");
    return;
  }
  for (PdDimension dim : {PdDimension::Solid3D, PdDimension::PlaneStrain})
    for (bool full : {false, true})
      for (bool aware : {false, true})
        for (bool alpha : {false, true})
          for (int threads : {1, 2}) {
            const Evaluation scalar =
                evaluate(dim, full, aware, alpha, threads, SimdTarget::Baseline);
            long broken = 0;
            for (long b : scalar.broken) broken += b;
            INFO("dimension " << static_cast<int>(dim) << ", full " << full << ", aware " << aware
                              << ", alpha " << alpha << ", threads " << threads);
            REQUIRE(scalar.broken[0] == 0);
            REQUIRE(broken > 0);
            for (std::size_t t = 1; t < targets.size(); ++t) {
              const Evaluation packed = evaluate(dim, full, aware, alpha, threads, targets[t]);
              INFO(simd_target_name(targets[t]));
              CHECK(packed.force == scalar.force);
              CHECK(packed.density == scalar.density);
              CHECK(packed.theta == scalar.theta);
              CHECK(packed.broken == scalar.broken);
              CHECK(packed.intact == scalar.intact);
              CHECK(packed.s0 == scalar.s0);
            }
          }
}
