// Every shipped problem holds the part of its own analysis (stages too), and asking a problem for
// another analysis's part is refused as a program error, whichever analysis it is.
#include "meshfree/spec/problem_spec.hpp"
#include <catch2/catch.hpp>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

using namespace mf;

namespace {

/// Which part the problem holds: 0 Galerkin (plane), 1 solid (3D Galerkin), 2 the 1D model,
/// 3 PD, 4 SPH, 5 staged.
std::size_t expected_part(const spec::ProblemSpec& p) {
  switch (p.analysis) {
  case spec::Analysis::ElasticStatic:
  case spec::Analysis::ElastoplasticStatic:
    return p.dimension == 3 ? 1 : 0;
  case spec::Analysis::ModelProblem1D:
    return 2;
  case spec::Analysis::Peridynamics:
    return 3;
  case spec::Analysis::Sph:
    return 4;
  case spec::Analysis::Staged:
    return 5;
  }
  return 99;
}

/// Checks the part `p` holds and that each accessor of another part throws.
void check_part(const spec::ProblemSpec& p) {
  INFO(p.name << " " << p.stage);
  const std::size_t own = expected_part(p);
  CHECK(p.part.index() == own);
  CHECK((own == 0) == p.is_galerkin());
  CHECK((own == 1) == p.is_solid());
  CHECK((own == 3) == p.is_pd());
  CHECK((own == 4) == p.is_sph());
  if (own != 0) CHECK_THROWS_AS(p.galerkin(), std::logic_error);
  if (own != 1) CHECK_THROWS_AS(p.solid(), std::logic_error);
  if (own != 2) CHECK_THROWS_AS(p.model_1d(), std::logic_error);
  if (own != 3) CHECK_THROWS_AS(p.pd(), std::logic_error);
  if (own != 4) CHECK_THROWS_AS(p.sph(), std::logic_error);
  if (own != 5) CHECK_THROWS_AS(p.staged(), std::logic_error);
  if (own <= 1)
    CHECK_NOTHROW(p.elasticity());
  else
    CHECK_THROWS_AS(p.elasticity(), std::logic_error);
  if (own == 5)
    for (const spec::ProblemSpec& stage : p.staged().stages) check_part(stage);
}

} // namespace

TEST_CASE("every shipped problem holds its own analysis's part and no other", "[input]") {
  std::set<std::size_t> seen;
  for (const auto& f :
       std::filesystem::directory_iterator(std::string(MESHFREE_SOURCE_DIR) + "/problems")) {
    if (f.path().extension() != ".yaml") continue;
    const spec::ProblemSpec p = spec::read_problem(f.path().string());
    seen.insert(p.part.index());
    check_part(p);
  }
  // The shipped problems cover every kind of part.
  CHECK(seen.size() == std::variant_size_v<spec::AnalysisPart>);
}
