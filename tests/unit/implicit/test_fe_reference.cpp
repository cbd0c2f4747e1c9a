// The two elastic plates of [Faraji 2007] against the external CalculiX reference kept in
// reference/calculix/ (see its README for how it was made): sampled displacements agree
// within 1% of the largest displacement component on each line.
#include "meshfree/implicit/elastic_solve.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace mf;

namespace {

struct RefLine {
  std::vector<Vec2> x, u;
};

RefLine read_reference(const std::string& problem, const std::string& line) {
  const std::string path = source_path("reference/calculix/" + problem + "/line_" + line + ".csv");
  std::ifstream in(path);
  REQUIRE(in.good());
  RefLine r;
  std::string row;
  std::getline(in, row); // header x,y,ux,uy
  while (std::getline(in, row)) {
    std::stringstream ss(row);
    double v[4];
    char comma;
    ss >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
    r.x.emplace_back(v[0], v[1]);
    r.u.emplace_back(v[2], v[3]);
  }
  return r;
}

void compare(const std::string& problem) {
  const auto spec = load_problem(problem);
  const auto result = implicit::solve_elastic_static(spec, test_session());
  for (const auto& [name, sample] : result.lines) {
    const RefLine ref = read_reference(problem, name);
    REQUIRE(ref.x.size() == sample.x.size());
    double umax[2] = {0, 0}, dmax[2] = {0, 0};
    for (std::size_t k = 0; k < ref.x.size(); ++k) {
      REQUIRE((ref.x[k] - sample.x[k]).norm() < 1e-9);
      for (int c = 0; c < 2; ++c) {
        umax[c] = std::max(umax[c], std::abs(ref.u[k](c)));
        dmax[c] = std::max(dmax[c], std::abs(ref.u[k](c) - sample.u[k](c)));
      }
    }
    std::cout << problem << " line " << name << ": max |du_x|/max|u_x| = " << dmax[0] / umax[0]
              << ", max |du_y|/max|u_y| = " << dmax[1] / umax[1] << "\n";
    CHECK(dmax[0] / umax[0] < 0.01);
    CHECK(dmax[1] / umax[1] < 0.01);
  }
}

} // namespace

TEST_CASE("square plate in tension agrees with CalculiX within 1% along y = 0.7 and the top",
          "[fe_reference]") {
  compare("plate_tension");
}

TEST_CASE("asymmetric 2 x 1 plate agrees with CalculiX within 1% along y = 0.7 and the top",
          "[fe_reference]") {
  compare("plate_asymmetric");
}
