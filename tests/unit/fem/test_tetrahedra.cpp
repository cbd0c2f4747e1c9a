// Tetrahedra: shape functions, quadrature rules against the exact moments of the reference
// tetrahedron, gmsh's tetrahedra of a prism (node order, volume, nodes on a hole's cylinder,
// boundary faces, refinement, the same mesh twice) and the point locator.
#include "meshfree/core/error.hpp"
#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/fem/tet_locator.hpp"
#include "meshfree/fem/tetrahedra.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace mf;

namespace {

double factorial(int n) {
  return n <= 1 ? 1.0 : n * factorial(n - 1);
}

/// The integral of x^a y^b z^c over the reference tetrahedron: a! b! c! / (a + b + c + 3)!.
double moment(int a, int b, int c) {
  return factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
}

/// Volume of a mesh by its own map (the 14-point rule: exact for straight and quadratic
/// elements, whose det J is of degree 3).
double mesh_volume(const fem::TetMesh& mesh) {
  const fem::TetRule rule = fem::tet_rule(5);
  double v = 0.0, N[fem::kTetMaxNodes];
  Vec3 dN[fem::kTetMaxNodes];
  for (int e = 0; e < mesh.element_count(); ++e)
    for (std::size_t q = 0; q < rule.xi.size(); ++q) {
      fem::tet_shape_functions(mesh.quadratic, rule.xi[q], N, dN);
      Mat3 J = Mat3::Zero();
      for (int a = 0; a < mesh.nodes_per_element(); ++a)
        J += mesh.x[mesh.element(e)[a]] * dN[a].transpose();
      v += rule.weight[q] * J.determinant();
    }
  return v;
}

/// The quarter of a 4 x 4 section with a hole of radius 1 at the corner (the thick cylinder).
geometry::Domain quarter_with_bore() {
  geometry::Domain d = geometry::Domain::rectangle({0.0, 0.0}, {4.0, 4.0});
  d.add_hole({{0.0, 0.0}, 1.0, "bore"});
  return d;
}

} // namespace

TEST_CASE("tetrahedron shape functions: nodal values, partition of unity, gradients",
          "[fem][tet]") {
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const int n = quadratic ? 10 : 4;
    const Vec3* ref = fem::tet_reference_nodes();
    double N[10], Np[10], Nm[10];
    Vec3 dN[10];
    for (int b = 0; b < n; ++b) {
      fem::tet_shape_functions(quadratic, ref[b], N, nullptr);
      for (int a = 0; a < n; ++a) REQUIRE(N[a] == Approx(a == b ? 1.0 : 0.0).margin(1e-15));
    }
    const Vec3 p(0.21, 0.17, 0.33);
    fem::tet_shape_functions(quadratic, p, N, dN);
    double sum = 0.0;
    Vec3 gsum = Vec3::Zero(), reproduced = Vec3::Zero();
    for (int a = 0; a < n; ++a) sum += N[a], gsum += dN[a], reproduced += N[a] * ref[a];
    REQUIRE(sum == Approx(1.0).epsilon(1e-15));
    REQUIRE(gsum.norm() < 1e-14);
    REQUIRE((reproduced - p).norm() < 1e-15);
    const double h = 1e-6;
    for (int d = 0; d < 3; ++d) {
      fem::tet_shape_functions(quadratic, p + h * Vec3::Unit(d), Np, nullptr);
      fem::tet_shape_functions(quadratic, p - h * Vec3::Unit(d), Nm, nullptr);
      for (int a = 0; a < n; ++a)
        REQUIRE(dN[a](d) == Approx((Np[a] - Nm[a]) / (2 * h)).margin(1e-9));
    }
  }
}

TEST_CASE("tetrahedron rules integrate every monomial of their degree exactly", "[fem][tet]") {
  for (int degree = 1; degree <= 9; ++degree) {
    CAPTURE(degree);
    const fem::TetRule r = fem::tet_rule(degree);
    for (double w : r.weight) REQUIRE(w > 0.0);
    for (const Vec3& x : r.xi) REQUIRE((x.minCoeff() > 0.0 && x.sum() < 1.0));
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c) {
          double q = 0.0;
          for (std::size_t k = 0; k < r.xi.size(); ++k)
            q += r.weight[k] * std::pow(r.xi[k].x(), a) * std::pow(r.xi[k].y(), b) *
                 std::pow(r.xi[k].z(), c);
          CAPTURE(a, b, c);
          REQUIRE(q == Approx(moment(a, b, c)).epsilon(1e-13));
        }
  }
  // The sizes asked for: 1, 4 and 14 points; and the 4-point rule is not exact beyond degree 2.
  REQUIRE(fem::tet_rule(1).xi.size() == 1);
  REQUIRE(fem::tet_rule(2).xi.size() == 4);
  REQUIRE(fem::tet_rule(3).xi.size() == 14);
  double q = 0.0;
  const fem::TetRule r = fem::tet_rule(2);
  for (std::size_t k = 0; k < r.xi.size(); ++k) q += r.weight[k] * std::pow(r.xi[k].x(), 3);
  REQUIRE(std::abs(q - moment(3, 0, 0)) > 1e-4 * moment(3, 0, 0));
}

TEST_CASE("tetrahedron faces: corners in order and outward normals", "[fem][tet]") {
  const Vec3* ref = fem::tet_reference_nodes();
  const Vec3 centroid(0.25, 0.25, 0.25);
  for (int f = 0; f < 4; ++f) {
    const int* c = fem::tet_face_corners(f);
    REQUIRE((fem::on_tet_face(f, {0.0, 0.0}) - ref[c[0]]).norm() == 0.0);
    REQUIRE((fem::on_tet_face(f, {1.0, 0.0}) - ref[c[1]]).norm() == 0.0);
    REQUIRE((fem::on_tet_face(f, {0.0, 1.0}) - ref[c[2]]).norm() == 0.0);
    Vec3 ds, dt;
    const Vec3 mid = fem::on_tet_face(f, {1.0 / 3.0, 1.0 / 3.0}, &ds, &dt);
    REQUIRE(ds.cross(dt).dot(mid - centroid) > 0.0);    // away from the inside
    for (int k = 0; k < 3; ++k) REQUIRE(c[k] != 3 - f); // opposite corner 3 - f
  }
}

TEST_CASE("gmsh tetrahedra of a box: gmsh's node order, orientation, volume, faces",
          "[fem][tet][gmsh]") {
  const geometry::Domain section = geometry::Domain::rectangle({0.0, 0.0}, {1.0, 0.75});
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const fem::TetMesh mesh = fem::mesh_prism(section, 0.5, 0.5, 0.25, {}, quadratic);
    REQUIRE(mesh.quadratic == quadratic);
    REQUIRE(mesh.element_count() > 50);
    for (int e = 0; e < mesh.element_count(); ++e) {
      REQUIRE(fem::tet_corner_volume6(mesh, e) > 0.0);
      if (!quadratic) continue;
      // Straight edges: each mid-edge node is the middle of the corners the order names.
      for (int k = 0; k < 6; ++k) {
        const int* ends = fem::tet_edge_corners(k);
        const int* n = mesh.element(e);
        REQUIRE((mesh.x[n[4 + k]] - 0.5 * (mesh.x[n[ends[0]]] + mesh.x[n[ends[1]]])).norm() <
                1e-12);
      }
    }
    for (const Vec3& x : mesh.x)
      REQUIRE(
          (x.z() >= 0.5 - 1e-12 && x.z() <= 1.0 + 1e-12 && section.contains(x.head<2>(), 1e-12)));
    REQUIRE(mesh_volume(mesh) == Approx(0.375).epsilon(1e-12));
    // The boundary's triangles cover its area 2 (1 x 0.75 + 1 x 0.5 + 0.75 x 0.5) exactly.
    double area = 0.0;
    for (const fem::TetFace& f : fem::boundary_faces(mesh)) {
      const int* c = fem::tet_face_corners(f.local_face);
      const int* n = mesh.element(f.element);
      area +=
          0.5 * (mesh.x[n[c[1]]] - mesh.x[n[c[0]]]).cross(mesh.x[n[c[2]]] - mesh.x[n[c[0]]]).norm();
    }
    REQUIRE(area == Approx(2.0 * 0.75 + 2.0 * 0.5 + 2.0 * 0.375).epsilon(1e-12));
  }
}

TEST_CASE("gmsh tetrahedra of a prism with a hole: nodes on the cylinder, volume",
          "[fem][tet][gmsh]") {
  const geometry::Domain section = quarter_with_bore();
  const double exact = (16.0 - M_PI / 4.0) * 0.5;
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const fem::TetMesh mesh = fem::mesh_prism(section, 0.0, 0.5, 0.25, {}, quadratic);
    int on_bore = 0;
    for (const Vec3& x : mesh.x) {
      REQUIRE(section.contains(x.head<2>(), 1e-9));
      if (std::abs(x.head<2>().norm() - 1.0) < 1e-6) {
        REQUIRE(x.head<2>().norm() == Approx(1.0).margin(1e-12));
        ++on_bore;
      }
    }
    REQUIRE(on_bore >= (quadratic ? 40 : 14));
    const double v = mesh_volume(mesh);
    if (quadratic) {
      // mid-edge nodes on the cylinder: the quadratic faces miss it by O(theta^4)
      REQUIRE(v == Approx(exact).epsilon(2e-5));
    } else {
      // flat faces: the polyhedron covers slivers of the bore, about theta^2 pi / 24 r^2 depth
      REQUIRE(v > exact);
      REQUIRE(v - exact < 0.01);
    }
  }
}

TEST_CASE("gmsh tetrahedra: refinement boxes through the depth, the same mesh twice",
          "[fem][tet][gmsh]") {
  const geometry::Domain section = geometry::Domain::rectangle({0.0, 0.0}, {2.0, 1.0});
  geometry::Refinement box;
  box.box = BoundingBox{Vec2(0.0, 0.0), Vec2(0.5, 0.5)};
  box.spacing = 0.05;
  const fem::TetMesh a = fem::mesh_prism(section, 0.0, 0.4, 0.2, {box}, false);
  const fem::TetMesh b = fem::mesh_prism(section, 0.0, 0.4, 0.2, {box}, false);
  REQUIRE(a.connectivity == b.connectivity);
  REQUIRE(a.x == b.x);
  // Mean edge length of the elements whose centroid lies in the box and far from it.
  double sum[2] = {0.0, 0.0};
  int count[2] = {0, 0};
  for (int e = 0; e < a.element_count(); ++e) {
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 4; ++k) c += 0.25 * a.x[a.element(e)[k]];
    const int where = c.x() < 0.45 && c.y() < 0.45 ? 0 : c.x() > 1.2 ? 1 : -1;
    if (where < 0) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        sum[where] += (a.x[a.element(e)[i]] - a.x[a.element(e)[j]]).norm(), ++count[where];
  }
  CHECK(sum[0] / count[0] == Approx(0.05).epsilon(0.35));
  CHECK(sum[1] / count[1] == Approx(0.2).epsilon(0.35));
  REQUIRE(mesh_volume(a) == Approx(0.8).epsilon(1e-12));
}

TEST_CASE("the tetrahedron locator finds every point of the body and nothing outside it",
          "[fem][tet][gmsh]") {
  const geometry::Domain section = quarter_with_bore();
  for (bool quadratic : {false, true}) {
    CAPTURE(quadratic);
    const fem::TetMesh mesh = fem::mesh_prism(section, 0.0, 0.5, 0.25, {}, quadratic);
    const fem::TetLocator locator(mesh);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int found = 0;
    for (int k = 0; k < 2000; ++k) {
      const Vec3 x(4.0 * u(rng), 4.0 * u(rng), 0.5 * u(rng));
      int e = -1;
      Vec3 xi;
      // Points within 0.02 of the bore are left out: the mesh's faces there are not the cylinder.
      if (x.head<2>().norm() < 1.02) {
        if (x.head<2>().norm() < 0.9) REQUIRE_FALSE(locator.locate(x, e, xi));
        continue;
      }
      REQUIRE(locator.locate(x, e, xi));
      double N[fem::kTetMaxNodes];
      fem::tet_shape_functions(quadratic, xi, N, nullptr);
      Vec3 back = Vec3::Zero();
      for (int a = 0; a < mesh.nodes_per_element(); ++a) back += N[a] * mesh.x[mesh.element(e)[a]];
      REQUIRE((back - x).norm() < 1e-12);
      ++found;
    }
    REQUIRE(found > 1500);
    int e = -1;
    Vec3 xi;
    REQUIRE_FALSE(locator.locate({2.0, 2.0, 0.5001}, e, xi));
    REQUIRE_FALSE(locator.locate({4.001, 2.0, 0.25}, e, xi));
    REQUIRE(locator.locate({4.0, 4.0, 0.5}, e, xi)); // a corner of the body
  }
}
