// Elastic runs record output.gauges as elastoplastic runs do (history.csv, ux_<name> ...): on the
// plane and the 3D patch tests, meshfree (with VCI, which makes the linear field exact) and
// finite elements, u^h at gauges off the nodes equals the exact linear displacement up to the
// penalty's gap at the held boundary (the largest |u^h - ubar| there: u^h is the exact field
// moved as a whole by about that much) and the quadrature's round-off (measured: plane 1.7e-9
// of |u| meshfree with VCI, 3D 2.8e-8 absolute against a gap of 2.7e-8, both methods).
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/verification/exact_solutions.hpp"
#include "meshfree/verification/exact_solutions_3d.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

using namespace mf;

namespace {

const std::vector<std::string> kMethods[2] = {{"discretisation.quadrature.correction=vci"},
                                              {"discretisation.method=fem"}};

std::string first_lines(const std::string& file) {
  std::ifstream in(file);
  std::string header, row;
  std::getline(in, header), std::getline(in, row);
  return header + "\n" + row;
}

} // namespace

TEST_CASE("a plane elastic run records its gauges: the patch test's exact displacement",
          "[elastic][gauges]") {
  const std::vector<Vec2> at{{0.37, 0.61}, {0.95, 0.05}};
  for (const auto& method : kMethods) {
    std::vector<std::string> set = method;
    set.push_back("output.gauges=[{name: a, at: [0.37, 0.61]}, {name: b, at: [0.95, 0.05]}]");
    const auto spec = load_problem("patch_test", set);
    const auto r = implicit::solve_elastic_static(spec, test_session());
    REQUIRE(r.gauge_u.size() == 2);
    const auto mat = materials::plane_stress_equivalent(spec.elasticity(), spec.model);
    for (std::size_t k = 0; k < at.size(); ++k) {
      const Vec2 exact = verification::exact_displacement(*spec.galerkin().exact, mat, at[k]);
      INFO(method.front() << ", gauge " << k << ": " << r.gauge_u[k].transpose() << " against "
                          << exact.transpose());
      CHECK((r.gauge_u[k] - exact).norm() <= 1.5 * r.violation_max + 1e-8 * exact.norm());
    }
    CHECK(r.violation_max <= 1e-8 * at.front().norm());
  }
}

TEST_CASE("a 3D elastic run records its gauges: the patch test's exact displacement",
          "[elastic][gauges][solid3d]") {
  const std::vector<Vec3> at{{0.31, 0.42, 0.17}, {0.9, 0.7, 0.45}};
  for (const auto& method : kMethods) {
    std::vector<std::string> set = method;
    set.push_back("output.gauges=[{name: a, at: [0.31, 0.42, 0.17]}, {name: b, at: [0.9, 0.7, "
                  "0.45]}]");
    const auto spec = load_problem("patch_test_3d", set);
    const auto r = implicit::solve_solid_elastic(spec, test_session());
    REQUIRE(r.gauge_u.size() == 2);
    double gap = 0.0;
    for (const implicit::FaceReport& f : r.boundary) gap = std::max(gap, f.violation_max);
    for (std::size_t k = 0; k < at.size(); ++k) {
      const Vec3 exact =
          verification::exact_displacement_3d(*spec.solid().exact, spec.elasticity(), at[k]);
      INFO(method.front() << ", gauge " << k << ": " << r.gauge_u[k].transpose() << " against "
                          << exact.transpose());
      CHECK((r.gauge_u[k] - exact).norm() <= 1.5 * gap + 1e-8 * exact.norm());
    }
    CHECK(gap <= 1e-6 * at.front().norm());
    // history.csv names them as the elastoplastic runs do.
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "meshfree_gauges";
    std::filesystem::remove_all(dir);
    {
      io::OutputDirectory out(dir.string());
      implicit::write_solid_elastic_outputs(spec, r, test_session(), out);
      out.commit();
    }
    const std::string csv = first_lines((dir / "history.csv").string());
    INFO(csv);
    CHECK(csv.find(",ux_a,uy_a,uz_a,ux_b,uy_b,uz_b,") != std::string::npos);
    std::filesystem::remove_all(dir);
  }
}
