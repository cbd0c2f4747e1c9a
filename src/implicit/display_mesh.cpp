#include "meshfree/implicit/display_mesh.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/geometry/delaunay.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/materials/elastic.hpp"
#include <array>
#include <tuple>

namespace mf::implicit {

namespace {

/// The elements of a finite-element mesh as triangles through its own nodes.
std::vector<int> triangles_of(const fem::Mesh& mesh) {
  // Local corners of each triangle: Q4 across its 0-2 diagonal; Q8 a corner triangle at each
  // corner and two through the mid-side nodes 4 (edge 0-1), 5, 6, 7 (edge 3-0).
  static const std::vector<std::array<int, 3>> t3{{0, 1, 2}}, q4{{0, 1, 2}, {0, 2, 3}},
      q8{{0, 4, 7}, {4, 1, 5}, {5, 2, 6}, {6, 3, 7}, {4, 5, 6}, {4, 6, 7}};
  const auto& split = mesh.type == fem::ElementType::T3   ? t3
                      : mesh.type == fem::ElementType::Q4 ? q4
                                                          : q8;
  std::vector<int> tri;
  tri.reserve(3 * split.size() * mesh.element_count());
  for (int e = 0; e < mesh.element_count(); ++e)
    for (const auto& t : split)
      for (int a : t) tri.push_back(mesh.element(e)[a]);
  return tri;
}

/// Each vertex its own node, with weight one.
ShapeTable identity_table(int n) {
  ShapeTable t;
  for (int i = 0; i < n; ++i) {
    t.node.push_back(i);
    t.phi.push_back(1.0);
    t.offset.push_back(i + 1);
  }
  return t;
}

/// Vertices and triangles over a meshfree body: a plain rectangle's structured grid, else the
/// nodes' Delaunay triangles in the body (no mesher to load: loading gmsh took 0.25 s of a
/// 0.6 s run), else, where those do not follow its boundary, gmsh's triangles.
std::pair<std::vector<Vec2>, std::vector<int>> meshfree_triangles(const spec::ProblemSpec& spec,
                                                                  const GalerkinModel& m) {
  if (!is_plain_rectangle(spec.domain, spec.galerkin().discretisation.refinement)) {
    const std::vector<Vec2>& nodes = m.node_positions();
    const std::vector<geometry::Triangle> tri = geometry::body_triangles(spec.domain, nodes);
    if (!tri.empty()) {
      std::vector<int> connectivity;
      connectivity.reserve(3 * tri.size());
      for (const geometry::Triangle& t : tri)
        connectivity.insert(connectivity.end(), t.begin(), t.end());
      return {nodes, std::move(connectivity)};
    }
    log::info("display mesh: the nodes' triangles do not follow the boundary; gmsh meshes it");
  }
  spec::ProblemSpec t3 = spec;
  spec::DiscretisationSpec& disc = t3.galerkin().discretisation;
  disc.fem.element = "t3";
  disc.fem.mesh.clear();
  fem::Mesh mesh = read_fe_mesh(t3);
  return {std::move(mesh.x), std::move(mesh.connectivity)};
}

} // namespace

DisplayMesh display_mesh(const spec::ProblemSpec& spec, const GalerkinModel& m) {
  DisplayMesh d;
  d.cells.xdmf_type = "Triangle";
  d.cells.nodes_per_cell = 3;
  if (m.fe) {
    d.x = m.fe->mesh.x;
    d.cells.connectivity = triangles_of(m.fe->mesh);
    d.table = identity_table(static_cast<int>(d.x.size()));
  } else {
    std::tie(d.x, d.cells.connectivity) = meshfree_triangles(spec, m);
    d.table = shapes_at(m, d.x, false);
  }
  log::info("display mesh: ", d.x.size(), " vertices, ", d.cells.connectivity.size() / 3,
            " triangles");
  return d;
}

const char* const DisplayFields::kNames[kScalars] = {"stress_xx", "stress_yy", "stress_xy",
                                                     "stress_zz", "von_mises", "plastic_strain"};

DisplayFields display_fields(const DisplayMesh& mesh, const std::vector<double>& d,
                             const NodalAverage& avg) {
  const ShapeTable& t = mesh.table;
  DisplayFields f;
  f.u.resize(t.rows());
  for (auto& v : f.values) v.resize(t.rows());
  for (int r = 0; r < t.rows(); ++r) {
    Vec3 s = Vec3::Zero();
    double szz = 0.0, alpha = 0.0;
    for (int q = t.offset[r]; q < t.offset[r + 1]; ++q) {
      const int I = t.node[q];
      s += t.phi[q] * avg.stress[I];
      szz += t.phi[q] * avg.stress_zz[I];
      alpha += t.phi[q] * avg.plastic_strain[I];
    }
    f.u[r] = displacement_at(t, r, d);
    const double v[DisplayFields::kScalars] = {s(0), s(1), s(2), szz, materials::von_mises(s, szz),
                                               alpha};
    for (int c = 0; c < DisplayFields::kScalars; ++c) f.values[c][r] = v[c];
  }
  return f;
}

std::pair<DisplayMesh, DisplayFields> elastic_display(const spec::ProblemSpec& spec,
                                                      const GalerkinModel& m,
                                                      const std::vector<double>& d,
                                                      const solvers::PetscSession& session) {
  const ShapeTable& t = m.domain_table;
  const PointLaws laws = point_laws(spec, domain_rows(m));
  std::vector<Vec3> stress(t.rows());
  std::vector<double> szz(t.rows());
  for (int k = 0; k < t.rows(); ++k)
    std::tie(stress[k], szz[k]) = laws.elastic_stress(spec.model, k, strain_at(t, k, d));
  const NodalAverage avg = nodal_average(m, stress, szz, session);
  std::pair<DisplayMesh, DisplayFields> out;
  session.collective([&] {
    if (session.rank() != 0) return;
    out.first = display_mesh(spec, m);
    out.second = display_fields(out.first, d, avg);
  });
  return out;
}

DisplaySeries::DisplaySeries(io::OutputDirectory* out, const DisplayMesh& mesh)
    : output_(out, "display_mesh", mesh.x, mesh.cells) {
  output_.vector2("displacement", [this](std::vector<Vec2>& v) { v = fields_.u; });
  for (int c = 0; c < DisplayFields::kScalars; ++c)
    output_.scalar(DisplayFields::kNames[c], fields_.values[c]);
}

void DisplaySeries::write(double time, DisplayFields fields) {
  fields_ = std::move(fields);
  output_.write(time);
}

} // namespace mf::implicit
