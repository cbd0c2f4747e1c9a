// Spherical holes in 3D bodies (implicit/solid_sphere_points, solid_points): the sphere's face
// points integrate its area exactly (the (w, phi) patches' area element r dw dphi is constant,
// and a plane normal to the pole axis cuts them along a latitude),
// ends and straight side faces the sphere cuts are plane bodies with exact arcs, the volume of
// the body converges as the cut cells are split, nodes keep out of the ball and its gap, and
// gmsh's tetrahedra name the sphere's boundary triangles.
#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/implicit/solid_sphere_points.hpp"
#include "meshfree/implicit/solid_tets.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

namespace {

/// The cube [0, 2.5]^3 minus the ball of radius 1 about its corner (an octant model's cavity).
geometry::Prism octant_cavity() {
  return geometry::Prism{geometry::Domain::rectangle({0.0, 0.0}, {2.5, 2.5}),
                         0.0,
                         2.5,
                         {geometry::Sphere{Vec3::Zero(), 1.0, "cavity"}}};
}

spec::DiscretisationSpec discretisation(double spacing, int cut_levels = 2) {
  spec::DiscretisationSpec d;
  d.spacing = d.cell_size = spacing;
  d.cut_levels = cut_levels;
  d.cut_arcs = true;
  return d;
}

double sum(const std::vector<double>& w) {
  double s = 0.0;
  for (double x : w) s += x;
  return s;
}

double face_area(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                 const std::string& face) {
  return sum(implicit::prism_face_points(body, d, {face}).weight);
}

} // namespace

TEST_CASE("sphere faces: exact areas, normals into the ball, cut faces of the prism",
          "[solid3d][sphere]") {
  const geometry::Prism body = octant_cavity();
  REQUIRE(body.face_names().back() == "cavity");
  for (double h : {0.5, 0.25, 0.2}) {
    CAPTURE(h);
    const spec::DiscretisationSpec d = discretisation(h);
    CHECK(face_area(body, d, "cavity") == Approx(M_PI / 2.0).epsilon(1e-13));
    // 2.5^2 minus a quarter disc, on the plane quadrature's exact arcs (good to about 1e-8)
    for (const char* cut : {"left", "bottom", "back"})
      CHECK(face_area(body, d, cut) == Approx(6.25 - M_PI / 4.0).epsilon(1e-7));
    CHECK(face_area(body, d, "front") == Approx(6.25).epsilon(1e-13));
    const implicit::SolidPoints on = implicit::prism_face_points(body, d, {"cavity"});
    for (std::size_t k = 0; k < on.x.size(); ++k) {
      REQUIRE(std::abs(on.x[k].norm() - 1.0) < 1e-13);
      REQUIRE((on.normal[k] + on.x[k]).norm() < 1e-13);
      REQUIRE(on.x[k].minCoeff() >= 0.0);
    }
  }
  // a whole sphere inside the body, not centred on a plane of the patches' grid
  const geometry::Prism inner{geometry::Domain::rectangle({0.0, 0.0}, {2.0, 2.0}),
                              0.0,
                              2.0,
                              {geometry::Sphere{Vec3(0.9, 1.1, 1.05), 0.6, "void"}}};
  CHECK(face_area(inner, discretisation(0.25), "void") == Approx(4.0 * M_PI * 0.36).epsilon(1e-13));
  // a sphere the end z = 0 cuts 0.3 below its centre: the cap of height 0.9 remains; the end is
  // a latitude of the patches, clipped exactly (area 2 pi r h)
  const geometry::Prism capped{geometry::Domain::rectangle({0.0, 0.0}, {2.0, 2.0}),
                               0.0,
                               2.0,
                               {geometry::Sphere{Vec3(1.0, 1.0, 0.3), 0.6, "cap"}}};
  CHECK(face_area(capped, discretisation(0.25), "cap") ==
        Approx(2.0 * M_PI * 0.6 * 0.9).epsilon(1e-12));
  CHECK(face_area(capped, discretisation(0.25), "back") ==
        Approx(4.0 - M_PI * (0.36 - 0.09)).epsilon(1e-7));
  // the same cap cut by the side x = 0 instead: the patches' pole axis turns to x, so the cut is
  // again a latitude
  const geometry::Prism side{geometry::Domain::rectangle({0.0, 0.0}, {2.0, 2.0}),
                             0.0,
                             2.0,
                             {geometry::Sphere{Vec3(0.3, 1.0, 1.0), 0.6, "cap"}}};
  CHECK(face_area(side, discretisation(0.25), "cap") ==
        Approx(2.0 * M_PI * 0.6 * 0.9).epsilon(1e-12));
  // cut by both the end z = 0 and the side x = 0 off its centre: the side's cut crosses the
  // latitudes, found by bisection along each; where a latitude's arc in the body stops being
  // whole the integrand has a square-root kink, so the area is good to 1e-4 only (measured 2.5e-5
  // with the default two cut levels). The reference: r times the integral over w from -0.3 to r
  // of the latitude's arc in x >= -0.3, 2 pi - 2 acos(0.3 / rho) where rho = sqrt(r^2 - w^2)
  // exceeds 0.3 (adaptive quadrature, split at the kink, scipy.integrate.quad).
  const geometry::Prism corner{geometry::Domain::rectangle({0.0, 0.0}, {2.0, 2.0}),
                               0.0,
                               2.0,
                               {geometry::Sphere{Vec3(0.3, 1.0, 0.3), 0.6, "cap"}}};
  CHECK(face_area(corner, discretisation(0.25), "cap") == Approx(2.4604095260).epsilon(1e-4));
}

TEST_CASE("sphere cavity: the body's volume and moments converge as cut cells split",
          "[solid3d][sphere]") {
  const geometry::Prism body = octant_cavity();
  const double exact = 2.5 * 2.5 * 2.5 - M_PI / 6.0;
  // int x dV: the cube's 2.5^4 / 2 less the ball's octant's pi r^4 / 16
  const double moment = 0.5 * std::pow(2.5, 4) - M_PI / 16.0;
  double previous = 1.0;
  for (int levels : {0, 1, 2, 3}) {
    CAPTURE(levels);
    const implicit::SolidPoints v =
        implicit::prism_volume_points(body, discretisation(0.25, levels));
    double volume = 0.0, mx = 0.0;
    for (std::size_t k = 0; k < v.x.size(); ++k) {
      REQUIRE(body.contains(v.x[k]));
      volume += v.weight[k];
      mx += v.weight[k] * v.x[k].x();
    }
    const double error = std::abs(volume / exact - 1.0);
    WARN("cut levels " << levels << ": volume error " << error << ", x-moment error "
                       << std::abs(mx / moment - 1.0));
    CHECK(error < previous);
    previous = error;
  }
}

TEST_CASE("sphere cavity: no node in the ball or its gap but those on its surface",
          "[solid3d][sphere]") {
  const geometry::Prism body = octant_cavity();
  for (double h : {0.5, 0.25}) {
    CAPTURE(h);
    const implicit::SolidNodes n = implicit::prism_nodes(body, discretisation(h));
    int on_surface = 0;
    for (std::size_t i = 0; i < n.x.size(); ++i) {
      const double d = body.spheres[0].distance(n.x[i]);
      REQUIRE(body.contains(n.x[i], 1e-12));
      if (std::abs(d) < 1e-12)
        ++on_surface;
      else
        REQUIRE(d >= 0.3 * h);
    }
    // the octant's rings: about (pi r / 2h) of them, of about (pi r / 2h) nodes at the equator
    const double rough = M_PI / 2.0 / (h * h);
    CHECK(on_surface > 0.5 * rough);
    CHECK(on_surface < 2.0 * rough);
  }
}

TEST_CASE("sphere cavity in gmsh's tetrahedra: the cavity's triangles named, its area",
          "[solid3d][sphere][tet][gmsh]") {
  const geometry::Prism body = octant_cavity();
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const implicit::TetElements fe(fem::mesh_prism(body, 0.25, {}, quadratic), body);
    const implicit::ElementPoints on = fe.face_points({"cavity"}, fe.default_order(), std::nullopt);
    // flat triangles are chords of the sphere (measured 1.1% short at size 0.25), quadratic
    // ones follow it (3.4e-5); the cut face and the volume: 0.12% and 0.07% in tet4, 7.6e-7 and
    // 1.8e-6 in tet10
    CHECK(sum(on.points.weight) == Approx(M_PI / 2.0).epsilon(quadratic ? 1e-4 : 2e-2));
    for (std::size_t k = 0; k < on.points.x.size(); ++k)
      REQUIRE(on.points.normal[k].dot(on.points.x[k]) < -0.9 * on.points.x[k].norm());
    CHECK(sum(fe.face_points({"left"}, fe.default_order(), std::nullopt).points.weight) ==
          Approx(6.25 - M_PI / 4.0).epsilon(quadratic ? 1e-5 : 3e-3));
    double volume = 0.0;
    for (double w : fe.body_points(2).points.weight) volume += w;
    CHECK(volume == Approx(2.5 * 2.5 * 2.5 - M_PI / 6.0).epsilon(quadratic ? 1e-5 : 3e-3));
  }
}
