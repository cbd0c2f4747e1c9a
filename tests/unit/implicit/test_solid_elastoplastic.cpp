// 3D elastoplastic analysis through the whole solver: a homogeneous block in uniaxial stress
// against the closed-form cyclic response (load, unload, reverse yielding with the Bauschinger
// effect), with Newton converging in few iterations on the consistent tangent.
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "test_support.hpp"
#include "uniaxial_response.hpp"
#include <catch2/catch.hpp>
#include <iostream>

using namespace mf;

namespace {

struct BlockRun {
  double error = 0.0; // largest reaction error relative to the largest stress
  int most_iterations = 0;
  long iterations = 0, tangents = 0, plastic_points = 0;
};

BlockRun block_run(std::vector<std::string> overrides) {
  overrides.push_back("discretisation.spacing=0.5");
  const auto spec = load_problem("block_uniaxial_3d", overrides);
  const auto r = implicit::solve_solid_elastoplastic(spec, test_session());
  REQUIRE(r.status == "completed");
  REQUIRE(r.increments.size() == 41);
  Uniaxial exact{std::get<materials::J2Parameters>(
      implicit::material_parameters(spec, spec.solid().material_index))};
  const double length = 2.0, area = 1.0;
  const std::size_t end = 3; // the condition that moves the end z = 2
  REQUIRE(spec.solid().boundary[end].name == "end");
  double worst = 0.0, largest = 0.0;
  BlockRun b;
  for (std::size_t k = 1; k < r.increments.size(); ++k) {
    const implicit::SolidIncrement& inc = r.increments[k];
    const double sigma = exact.stress(inc.record.factors[end] / length);
    worst = std::max(worst, std::abs(inc.faces[end].force.z() - sigma * area));
    largest = std::max(largest, std::abs(sigma));
    b.most_iterations = std::max(b.most_iterations, inc.record.newton.iterations);
    b.iterations += inc.record.newton.iterations;
    b.tangents += inc.record.newton.tangents;
  }
  b.error = worst / largest;
  b.plastic_points = r.increments.back().record.plastic_points;
  return b;
}

} // namespace

TEST_CASE("a 3D block in uniaxial stress follows the closed-form cyclic response",
          "[elastoplastic][solid3d]") {
  const BlockRun b = block_run({});
  std::cout << "3D block: largest reaction error relative to the largest stress " << b.error
            << ", at most " << b.most_iterations << " Newton iterations per increment\n";
  // Measured 7.2e-7 (the penalty's compliance and the nominal stretch; without plasticity's
  // Bauschinger effect the compression branch would be off by 10%), 2 iterations.
  CHECK(b.error < 2e-6);
  CHECK(b.most_iterations <= 4);
  CHECK(b.plastic_points > 0);
}

TEST_CASE("a 3D block with kept tangents follows the same closed-form cyclic response",
          "[elastoplastic][solid3d][newton]") {
  // Modified Newton in 3D (three DOFs a node, the same solver): the closed form to the same
  // bound as Newton's method, from fewer tangents than iterations.
  const BlockRun b = block_run({"nonlinear.keep_tangent=0.25"});
  std::cout << "3D block, kept tangents: reaction error " << b.error << ", " << b.tangents
            << " tangents for " << b.iterations << " iterations\n";
  CHECK(b.error < 2e-6);
  CHECK(b.tangents < b.iterations);
  CHECK(b.plastic_points > 0);
}
