// Tetrahedra of a prism as the 3D model sees them (implicit/solid_tets): the named faces' areas
// and outward normals (the boundary closed: the sum of n dA over every face vanishes), box
// clipping, the body's volume, and shapes at arbitrary points reproducing linear fields.
#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/implicit/solid_tets.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

namespace {

/// The thick cylinder's prism: the quarter of a 4 x 4 section with the bore of radius 1 at the
/// corner, extruded from z = 0 by 0.5.
geometry::Prism cylinder_prism() {
  geometry::Domain d = geometry::Domain::rectangle({0.0, 0.0}, {4.0, 4.0});
  d.add_hole({{0.0, 0.0}, 1.0, "bore"});
  return geometry::Prism{d, 0.0, 0.5, {}};
}

implicit::TetElements tets(const geometry::Prism& body, bool quadratic) {
  return implicit::TetElements(
      fem::mesh_prism(body.section, body.z0, body.depth, 0.25, {}, quadratic), body);
}

double sum(const std::vector<double>& w) {
  double s = 0.0;
  for (double x : w) s += x;
  return s;
}

} // namespace

TEST_CASE("tetrahedra of a prism: face areas, outward normals, a closed boundary",
          "[solid3d][tet][gmsh]") {
  const geometry::Prism body = cylinder_prism();
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const implicit::TetElements fe = tets(body, quadratic);
    const auto area = [&](const std::string& face) {
      return sum(fe.face_points({face}, fe.default_order(), std::nullopt).points.weight);
    };
    CHECK(area("left") == Approx(1.5).epsilon(1e-12));
    CHECK(area("right") == Approx(2.0).epsilon(1e-12));
    // Flat triangles on the cylinder are chords (short of the arc by theta^2 / 24), quadratic
    // ones miss it by O(theta^4).
    CHECK(area("bore") == Approx(M_PI / 4.0).epsilon(quadratic ? 1e-5 : 5e-3));
    CHECK(area("front") == Approx(16.0 - M_PI / 4.0).epsilon(quadratic ? 1e-5 : 1e-3));
    const implicit::ElementPoints all = fe.face_points(body.face_names(), 1, std::nullopt);
    Vec3 closed = Vec3::Zero();
    for (std::size_t r = 0; r < all.points.x.size(); ++r) {
      closed += all.points.weight[r] * all.points.normal[r];
      const Vec3& x = all.points.x[r];
      const Vec3& n = all.points.normal[r];
      if (std::abs(x.x() - 4.0) < 1e-12) REQUIRE((n - Vec3(1, 0, 0)).norm() < 1e-12);
      if (std::abs(x.z()) < 1e-12) REQUIRE((n - Vec3(0, 0, -1)).norm() < 1e-12);
      if (x.head<2>().norm() < 1.0 + 1e-3) // on the bore: the normal points to the axis
        REQUIRE(n.head<2>().dot(x.head<2>()) / x.head<2>().norm() < -0.98);
    }
    REQUIRE(closed.norm() < 1e-13);
    REQUIRE(sum(fe.body_points(fe.default_order()).points.weight) ==
            Approx((16.0 - M_PI / 4.0) * 0.5).epsilon(quadratic ? 2e-5 : 1e-2));
    // A box holding the whole face keeps all of it; a box whose edge x = 2 cuts the Delaunay
    // triangles is refused (its Gauss points would load whole triangles past the edge).
    const spec::Box whole{{-1.0, -1.0, 0.4}, {5.0, 5.0, 1.0}};
    CHECK(sum(fe.face_points({"front"}, 2, whole).points.weight) ==
          Approx(sum(fe.face_points({"front"}, 2, std::nullopt).points.weight)).epsilon(1e-14));
    const spec::Box cutting{{2.0, -1.0, -1.0}, {5.0, 5.0, 1.0}};
    CHECK_THROWS_WITH(fe.face_points({"front"}, 2, cutting), Catch::Contains("element borders"));
  }
}

TEST_CASE("tetrahedra of a prism: shapes at points reproduce linear and quadratic fields",
          "[solid3d][tet][gmsh]") {
  const geometry::Prism body = cylinder_prism();
  const std::vector<Vec3> at = {
      {1.7, 0.2, 0.1}, {3.9, 3.9, 0.5}, {0.6, 1.5, 0.25}, {2.0, 2.0, 0.0}};
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const implicit::TetElements fe = tets(body, quadratic);
    const implicit::ElementPoints p = fe.shapes_at(at, true);
    REQUIRE(p.points.x.size() == at.size());
    const auto field = [&](const Vec3& x) {
      return 0.3 + 2.0 * x.x() - x.y() + 0.5 * x.z() + (quadratic ? 0.7 * x.x() * x.z() : 0.0);
    };
    for (std::size_t r = 0; r < at.size(); ++r) {
      double value = 0.0, unity = 0.0;
      Vec3 gradient = Vec3::Zero();
      for (int k = p.offset[r]; k < p.offset[r + 1]; ++k) {
        const Vec3& xI = fe.nodes()[p.node[k]];
        value += p.phi[k] * field(xI);
        gradient += p.dphi[k] * field(xI);
        unity += p.phi[k];
        if (k > p.offset[r]) REQUIRE(p.node[k] > p.node[k - 1]);
      }
      const Vec3& x = at[r];
      REQUIRE((p.points.x[r] - x).norm() < 1e-12);
      REQUIRE(unity == Approx(1.0).epsilon(1e-13));
      REQUIRE(value == Approx(field(x)).epsilon(1e-12));
      const Vec3 exact(2.0 + (quadratic ? 0.7 * x.z() : 0.0), -1.0,
                       0.5 + (quadratic ? 0.7 * x.x() : 0.0));
      REQUIRE((gradient - exact).norm() < 1e-11);
    }
    REQUIRE_THROWS(fe.shapes_at({{0.2, 0.2, 0.25}})); // in the bore
  }
}
