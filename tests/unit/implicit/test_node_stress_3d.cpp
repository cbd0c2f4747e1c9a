// The stress and equivalent plastic strain of a 3D body at its nodes in fields.h5 (the Gauss
// points' values averaged with weights phi^2 w, implicit/nodal_sums.hpp), as plane bodies have
// them: the 3D patch test's exact constant stress at every node (elastic), and the homogeneous
// block's uniaxial stress and plastic strain at every node after reverse yielding
// (elastoplastic), meshfree and 20-node bricks.
#include "hdf5_read.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/solid_elastic.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "meshfree/verification/exact_solutions_3d.hpp"
#include "test_support.hpp"
#include "uniaxial_response.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>

using namespace mf;

namespace {

/// Dataset `name` of the last step of an HDF5 field series.
std::vector<double> last_step(const std::string& file, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  hsize_t objects = 0;
  H5Gget_num_objs(f, &objects); // the steps and the geometry group
  H5Fclose(f);
  char group[32];
  std::snprintf(group, sizeof group, "/step_%06d/", static_cast<int>(objects) - 2);
  return read_doubles(file, group + name);
}

} // namespace

TEST_CASE("a 3D elastic body's stress at its nodes is the patch test's exact stress",
          "[solid3d][fields]") {
  for (const char* method : {"meshfree", "fem"}) {
    const auto spec =
        load_problem("patch_test_3d", {std::string("discretisation.method=") + method});
    const auto r = implicit::solve_solid_elastic(spec, test_session());
    REQUIRE(r.node_stress.size() == 6 * r.node_x.size());
    double worst = 0.0, largest = 0.0;
    for (std::size_t I = 0; I < r.node_x.size(); ++I) {
      const implicit::Vec6 exact =
          verification::exact_stress_3d(*spec.solid().exact, spec.elasticity(), r.node_x[I]);
      const implicit::Vec6 s = Eigen::Map<const implicit::Vec6>(r.node_stress.data() + 6 * I);
      worst = std::max(worst, (s - exact).cwiseAbs().maxCoeff());
      largest = std::max(largest, exact.cwiseAbs().maxCoeff());
    }
    INFO(method << ": largest nodal stress error " << worst / largest << " of the largest stress");
    CHECK(largest > 0.0);
    CHECK(worst <= 1e-9 * largest);
  }
}

TEST_CASE("a 3D elastoplastic body's stress and plastic strain at its nodes are its points'",
          "[solid3d][fields][elastoplastic]") {
  for (const char* method : {"meshfree", "fem"}) {
    double sigma = 0.0, alpha = 0.0;
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / (std::string("meshfree_node_stress_") + method);
    std::filesystem::remove_all(dir);
    {
      io::OutputDirectory out(dir.string());
      const auto spec =
          load_problem("block_uniaxial_3d", {"discretisation.spacing=0.5",
                                             std::string("discretisation.method=") + method});
      const auto r = implicit::solve_solid_elastoplastic(spec, test_session(), &out);
      REQUIRE(r.status == "completed");
      out.commit();
      // The closed form along the whole path (the end z = 2 moves by the factor of `end`).
      Uniaxial exact{std::get<materials::J2Parameters>(
          implicit::material_parameters(spec, spec.solid().material_index))};
      for (const implicit::SolidIncrement& inc : r.increments)
        if (!inc.record.factors.empty()) sigma = exact.stress(inc.record.factors[3] / 2.0);
      alpha = exact.alpha;
    }
    // The block is homogeneous: its Gauss points have one stress and plastic strain up to the
    // penalty's trace at its held faces, and a positive average of them lies within their range.
    // The last state follows reverse yielding and reloading.
    const std::string fields = (dir / "fields.h5").string();
    const std::string points = (dir / "gauss_points.h5").string();
    for (const char* name : {"stress_zz", "plastic_strain", "stress_xx", "von_mises"}) {
      const std::vector<double> at_nodes = last_step(fields, name);
      const std::vector<double> at_points = last_step(points, name);
      REQUIRE(!at_nodes.empty());
      const auto [lo, hi] = std::minmax_element(at_points.begin(), at_points.end());
      const double scale = name[0] == 'p' ? 1e-2 : 250.0; // a plastic strain, a yield stress
      double outside = 0.0;
      for (double v : at_nodes) outside = std::max({outside, *lo - v, v - *hi});
      INFO(method << ", " << name << ": the points' range [" << *lo << ", " << *hi
                  << "], the nodes at most " << outside << " outside it");
      CHECK(outside <= 1e-12 * scale);
      CHECK(*hi - *lo <= 1e-8 * scale);
    }
    // And they are the closed-form uniaxial response's, within the penalty's gap at the held
    // faces (the block's reactions are held to 2e-6 in test_solid_elastoplastic.cpp; 2.9e-8
    // and 1.4e-7 here).
    const double zz = last_step(fields, "stress_zz").front();
    const double eq = last_step(fields, "plastic_strain").front();
    INFO(method << ": stress_zz " << zz << " against " << sigma << ", plastic strain " << eq
                << " against " << alpha);
    CHECK(std::abs(zz - sigma) <= 2e-6 * std::abs(sigma));
    CHECK(std::abs(eq - alpha) <= 2e-6 * alpha);
    CHECK(alpha > 1e-3); // it has yielded
    std::filesystem::remove_all(dir);
  }
}
