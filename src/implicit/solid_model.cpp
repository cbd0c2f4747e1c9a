#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/implicit/point_coupling.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/implicit/volumetric_projection.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/verification/exact_solutions_3d.hpp"
#include <algorithm>
#include <numeric>

namespace mf::implicit {

namespace {

/// Traction sigma n from a Voigt stress [xx, yy, zz, yz, xz, xy].
Vec3 traction(const Vec6& s, const Vec3& n) {
  return {s(0) * n.x() + s(5) * n.y() + s(4) * n.z(), s(5) * n.x() + s(1) * n.y() + s(3) * n.z(),
          s(4) * n.x() + s(3) * n.y() + s(2) * n.z()};
}

/// VCI in 3D (implicit/integration_correction.hpp): grad~ Psi_I = grad Psi_I + xi_I Psi_I with
/// xi_I = (int_Gamma Psi_I n - sum_g w_g grad Psi_I) / sum_g w_g Psi_I, the boundary integral
/// over every face of the prism.
void correct_test_gradients_3d(const spec::ProblemSpec& spec, SolidModel& m,
                               const solvers::PetscSession& session) {
  const int N = m.node_count();
  std::vector<double> sums(7 * static_cast<std::size_t>(N), 0.0);
  SolidShapeTable& t = m.domain_table;
  for (int k = 0; k < t.rows(); ++k) {
    const double w = m.domain_weight[k];
    for (int j = t.offset[k]; j < t.offset[k + 1]; ++j) {
      double* s = sums.data() + 7 * static_cast<std::size_t>(t.node[j]);
      for (int c = 0; c < 3; ++c) s[c] += w * t.dphi[j](c);
      s[3] += w * t.phi[j];
    }
  }
  const SolidPoints faces =
      prism_face_points(m.body, spec.solid().discretisation, m.body.face_names());
  const Csr support = m.space->support_lists(faces.x);
  const RankPoints mine = rank_points(support, m.own, N, session);
  const SolidShapeTable e = m.space->shape_table(faces.x, mine.rows, support, false);
  for (int k = 0; k < e.rows(); ++k) {
    const Vec3 wn = faces.weight[mine.rows[k]] * faces.normal[mine.rows[k]];
    for (int j = e.offset[k]; j < e.offset[k + 1]; ++j) {
      double* s = sums.data() + 7 * static_cast<std::size_t>(e.node[j]);
      for (int c = 0; c < 3; ++c) s[4 + c] += e.phi[j] * wn(c);
    }
  }
  std::vector<double> xi(3 * static_cast<std::size_t>(N), 0.0);
  int bare = -1;
  for (int I = m.own.begin; I < m.own.end; ++I) {
    const double* s = sums.data() + 7 * static_cast<std::size_t>(I);
    if (!(s[3] > 0.0)) {
      bare = I;
      continue;
    }
    for (int c = 0; c < 3; ++c) xi[3 * I + c] = (s[4 + c] - s[c]) / s[3];
  }
  solvers::sum_everywhere(session.comm(), xi.data(), static_cast<int>(xi.size()));
  bare = static_cast<int>(solvers::max_everywhere(session.comm(), static_cast<double>(bare)));
  // As in the plane (integration_correction.cpp): no point in the support, or a support much
  // smaller than its neighbours'.
  if (bare >= 0) {
    const Vec3 x = m.node_positions()[bare];
    fail("VCI: the shape function of node ", bare, " at (", x.x(), ", ", x.y(), ", ", x.z(),
         ") does not integrate to a positive amount over the body's integration points");
  }
  t.test_dphi.resize(t.dphi.size());
  for (std::size_t j = 0; j < t.dphi.size(); ++j) {
    const double* x = xi.data() + 3 * static_cast<std::size_t>(t.node[j]);
    t.test_dphi[j] = t.dphi[j] + t.phi[j] * Vec3(x[0], x[1], x[2]);
  }
}

void build_points(const spec::ProblemSpec& spec, SolidModel& m) {
  const spec::SolidSpec& s = spec.solid();
  m.domain = prism_volume_points(m.body, s.discretisation);
  m.conditions.resize(s.boundary.size());
  for (std::size_t b = 0; b < s.boundary.size(); ++b) {
    const spec::FaceCondition& bc = s.boundary[b];
    m.conditions[b].bc = &bc;
    try {
      m.conditions[b].points = prism_face_points(m.body, s.discretisation, bc.faces, bc.box);
    } catch (const Error& e) {
      fail(bc.key_path, ".box: ", e.what());
    }
    MF_REQUIRE(!m.conditions[b].points.x.empty(), bc.key_path,
               ": no point of the named faces lies in its box");
  }
}

void build_tables(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                  SolidModel& m) {
  couple_points(m, session, [&](Csr support) {
    return spec.solid().discretisation.cell_mean_volumetric ? cell_supports(support, m.domain.cell)
                                                            : support;
  });
  m.domain_table = m.space->shape_table(m.domain.x, m.domain_mine.rows, m.domain_support, true);
  for (auto& c : m.conditions) {
    c.table = m.space->shape_table(c.points.x, c.mine.rows, c.support, false);
    c.values = face_values(spec, *c.bc, c.points, c.mine.rows);
  }
}

/// The element of each element point: rows listing the same nodes in a run are one element's.
std::vector<int> elements_of(const ElementPoints& b) {
  std::vector<int> element;
  const int rows = static_cast<int>(b.offset.size()) - 1;
  for (int r = 0; r < rows; ++r) {
    const bool same =
        r > 0 && std::equal(b.node.begin() + b.offset[r - 1], b.node.begin() + b.offset[r],
                            b.node.begin() + b.offset[r], b.node.begin() + b.offset[r + 1]);
    element.push_back(r == 0 ? 0 : element.back() + (same ? 0 : 1));
  }
  return element;
}

/// This rank's rows of element points as a shape table.
SolidShapeTable element_table(const ElementPoints& b, const std::vector<int>& rows) {
  SolidShapeTable t;
  for (int r : rows) {
    for (int k = b.offset[r]; k < b.offset[r + 1]; ++k) {
      t.node.push_back(b.node[k]);
      t.phi.push_back(b.phi[k]);
      if (!b.dphi.empty()) t.dphi.push_back(b.dphi[k]);
    }
    t.offset.push_back(static_cast<int>(t.node.size()));
  }
  return t;
}

Csr rows_of(const ElementPoints& b) {
  Csr c;
  c.offset = b.offset;
  c.index = b.node;
  return c;
}

/// Finite elements: the elements' points, the face conditions' points on the elements' faces,
/// the rows of this rank and their tables.
void build_elements(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                    PhaseTimer& timer, SolidModel& m) {
  const spec::SolidSpec& s = spec.solid();
  const spec::DiscretisationSpec& d = s.discretisation;
  {
    PhaseTimer::Scope scope(timer, "nodes");
    m.fe = make_solid_elements(d, m.body);
  }
  const int order = default_fe_order(spec, d, m.fe->default_order());
  ElementPoints body;
  std::vector<ElementPoints> faces(s.boundary.size());
  {
    PhaseTimer::Scope scope(timer, "quadrature");
    body = m.fe->body_points(order);
    for (std::size_t b = 0; b < s.boundary.size(); ++b) try {
        faces[b] = m.fe->face_points(s.boundary[b].faces, order, s.boundary[b].box);
      } catch (const Error& e) {
        fail(s.boundary[b].key_path, ".box: ", e.what());
      }
  }
  const int N = m.node_count();
  m.own = solvers::owned_nodes(N, session.rank(), session.size());
  PhaseTimer::Scope scope(timer, "shape_functions");
  m.domain = body.points;
  m.domain.cell = elements_of(body);
  m.domain_support = rows_of(body);
  m.domain_mine = rank_points(m.domain_support, m.own, N, session);
  std::vector<const Csr*> coupling{&m.domain_support};
  m.conditions.resize(s.boundary.size());
  for (std::size_t b = 0; b < s.boundary.size(); ++b) {
    SolidConditionPoints& c = m.conditions[b];
    c.bc = &s.boundary[b];
    MF_REQUIRE(!faces[b].points.x.empty(), c.bc->key_path, ": the elements have no face there");
    c.points = faces[b].points;
    c.support = rows_of(faces[b]);
    if (c.bc->constrains) coupling.push_back(&c.support);
    c.mine = rank_points(c.support, m.own, N, session);
    c.table = element_table(faces[b], c.mine.rows);
    c.values = face_values(spec, *c.bc, c.points, c.mine.rows);
  }
  m.pattern = coupling_pattern(coupling, N, m.own.begin, m.own.end);
  m.domain_table = element_table(body, m.domain_mine.rows);
}

/// The domain table's rows in columns along z for threaded assembly, and their weights.
void group_points(SolidModel& m) {
  std::vector<Vec2> at, nodes;
  for (int r : m.domain_mine.rows) {
    m.domain_weight.push_back(m.domain.weight[r]);
    at.push_back(m.domain.x[r].head<2>());
  }
  for (const Vec3& x : m.node_positions()) nodes.push_back(x.head<2>());
  m.domain_groups = PointGroups(m.domain_table.offset, m.domain_table.node, at, nodes);
}

} // namespace

std::vector<Vec3> face_values(const spec::ProblemSpec& spec, const spec::FaceCondition& bc,
                              const SolidPoints& pts, const std::vector<int>& rows) {
  const materials::IsotropicElastic m = spec.elasticity();
  const auto& exact = spec.solid().exact;
  std::vector<Vec3> out;
  for (int r : rows) {
    if (bc.constrains)
      out.push_back(bc.value_from_exact ? verification::exact_displacement_3d(*exact, m, pts.x[r])
                                        : bc.value);
    else if (bc.pressure_load)
      out.push_back(-bc.pressure * pts.normal[r]); // t = -p n, n the outward normal
    else
      out.push_back(
          bc.traction_from_exact
              ? traction(verification::exact_stress_3d(*exact, m, pts.x[r]), pts.normal[r])
              : bc.traction);
  }
  return out;
}

std::vector<Vec3> nodal_displacements(const SolidModel& m, const std::vector<double>& d) {
  const int N = m.node_count();
  std::vector<Vec3> u(N);
  if (m.fe) {
    for (int I = 0; I < N; ++I) u[I] = Vec3(d[3 * I], d[3 * I + 1], d[3 * I + 2]);
    return u;
  }
  const std::vector<Vec3>& x = m.node_positions();
  std::vector<int> all(N);
  std::iota(all.begin(), all.end(), 0);
  const SolidShapeTable t = m.space->shape_table(x, all, m.space->support_lists(x), false);
  for (int I = 0; I < N; ++I) u[I] = solid_displacement_at(t, I, d);
  return u;
}

SolidModel build_solid_model(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                             PhaseTimer& timer) {
  const spec::SolidSpec& s = spec.solid();
  SolidModel m;
  m.body = s.body(spec.domain);
  session.collective([&] {
    if (s.discretisation.method == spec::Method::Fem) {
      build_elements(spec, session, timer, m);
    } else {
      {
        PhaseTimer::Scope scope(timer, "nodes");
        m.space =
            std::make_unique<SolidSpace>(prism_nodes(m.body, s.discretisation),
                                         s.discretisation.shape, s.discretisation.dilation.x());
      }
      {
        PhaseTimer::Scope scope(timer, "quadrature");
        build_points(spec, m);
      }
      m.own = solvers::owned_nodes(m.node_count(), session.rank(), session.size());
      PhaseTimer::Scope scope(timer, "shape_functions");
      build_tables(spec, session, m);
    }
    group_points(m);
  });
  if (s.discretisation.vci && !m.fe) correct_test_gradients_3d(spec, m, session);
  take_cell_means(m, m.domain.cell, s.discretisation);
  return m;
}

namespace {

SolidShapeTable plain_shapes_at(const SolidModel& m, const std::vector<Vec3>& x, bool gradients) {
  std::vector<int> rows(x.size());
  std::iota(rows.begin(), rows.end(), 0);
  if (m.fe) return element_table(m.fe->shapes_at(x, gradients), rows);
  return m.space->shape_table(x, rows, m.space->support_lists(x), gradients);
}

} // namespace

SolidShapeTable solid_shapes_at(const SolidModel& m, const std::vector<Vec3>& x, bool gradients) {
  SolidShapeTable t = plain_shapes_at(m, x, gradients);
  if (gradients && m.cell_mean)
    sample_cell_means(CellPoints<3>{m.domain.x, m.domain.weight, m.domain.cell, m.cell_reach}, x, t,
                      [&m](const std::vector<Vec3>& at) { return plain_shapes_at(m, at, true); });
  return t;
}

std::string describe_solid_method(const spec::ProblemSpec& spec) {
  const spec::DiscretisationSpec& d = spec.solid().discretisation;
  const char* volumetric = d.cell_mean_volumetric ? ", volumetric strain of the cell's mean" : "";
  const geometry::Prism body = spec.solid().body(spec.domain);
  if (d.method == spec::Method::Fem && (d.fem.element == "tet4" || d.fem.element == "tet10"))
    return detail::concat("FE ", d.fem.element, " (gmsh's tetrahedra of the prism), spacing ",
                          d.spacing, volumetric);
  if (d.method == spec::Method::Fem)
    return detail::concat("FE ", d.fem.element, " (the plane ", spec::plane_element(d.fem.element),
                          " mesh extruded in ",
                          prism_slabs(body, d.spacing, d.spacing, d.refinement, 0.0).size(),
                          " layers of elements), spacing ", d.spacing, volumetric);
  return detail::concat(
      "meshfree RK (", d.shape.basis == kernels::Basis::Quadratic ? "quadratic" : "linear",
      " basis, ", d.shape.support == kernels::SupportShape::Circular ? "spherical" : "box",
      " supports), 3D, spacing ", d.spacing, " (", node_levels(body, d).size(),
      " levels of nodes along z), dilation ", d.dilation.x(), d.vci ? ", VCI" : "", volumetric);
}

SolidCounts count_model(const spec::ProblemSpec& spec, const SolidModel& m) {
  SolidCounts c;
  c.nodes = m.node_count();
  c.dofs = 3 * c.nodes;
  c.domain_points = static_cast<int>(m.domain.x.size());
  for (const auto& b : m.conditions) c.boundary_points += static_cast<int>(b.points.x.size());
  c.mean_support = static_cast<double>(m.domain_support.index.size()) /
                   std::max<std::size_t>(1, m.domain.x.size());
  log::info(describe_solid_method(spec), ": ", c.nodes, " nodes, ", c.dofs, " DOFs, ",
            c.domain_points, " domain points, ", c.boundary_points, " boundary points, ",
            c.mean_support, " nodes per point");
  return c;
}

FaceReport face_report(const SolidConditionPoints& c, const std::vector<double>& d, double factor,
                       const solvers::PetscSession& session) {
  FaceReport rep;
  rep.name = c.bc->name;
  rep.constraint = c.bc->constrains;
  double sums[5] = {0, 0, 0, 0, 0}, gap_max = 0.0; // force, int u.n, area
  for (int k = 0; k < c.table.rows(); ++k) {
    if (!c.mine.counted[k]) continue;
    const int row = c.mine.rows[k];
    const double w = c.points.weight[row];
    const Vec3 u = solid_displacement_at(c.table, k, d);
    Vec3 g = factor * w * c.values[k];
    if (c.bc->constrains) {
      const Vec3 gap = (u - factor * c.values[k]).cwiseProduct(c.bc->mask);
      g = -c.bc->penalty * w * gap;
      gap_max = std::max(gap_max, gap.norm());
    }
    for (int i = 0; i < 3; ++i) sums[i] += g(i);
    sums[3] += w * u.dot(c.points.normal[row]);
    sums[4] += w;
  }
  solvers::sum_everywhere(session.comm(), sums, 5);
  rep.force = Vec3(sums[0], sums[1], sums[2]);
  rep.normal_displacement = sums[4] > 0.0 ? sums[3] / sums[4] : 0.0;
  rep.violation_max = solvers::max_everywhere(session.comm(), gap_max);
  return rep;
}

namespace {

/// ", its box spans A on that plane" where the faces a box cuts lie in one plane normal to an
/// axis (A: the box's extent across it, which the loaded area equals unless the box reaches past
/// the faces), ", in its box" otherwise.
std::string box_area_text(const spec::Box& box, const std::vector<Vec3>& normal) {
  if (normal.empty()) return ", in its box";
  int axis = -1;
  for (int c = 0; c < 3; ++c)
    if (std::abs(std::abs(normal[0](c)) - 1.0) < 1e-12) axis = c;
  for (const Vec3& n : normal)
    if (axis < 0 || (n - normal[0]).norm() > 1e-12) return ", in its box";
  double spans = 1.0;
  for (int c = 0; c < 3; ++c)
    if (c != axis) spans *= box.hi(c) - box.lo(c);
  return detail::concat(", its box spans ", spans, " on that plane");
}

} // namespace

void print_solid_plan(const spec::ProblemSpec& spec, std::ostream& os) {
  const spec::SolidSpec& s = spec.solid();
  const geometry::Prism body = s.body(spec.domain);
  double n = 0.0;
  if (s.discretisation.method == spec::Method::Fem) {
    const std::unique_ptr<SolidElements> fe = make_solid_elements(s.discretisation, body);
    n = fe->node_count();
    os << "  " << fe->summary() << ", " << 3 * n << " DOFs\n";
  } else {
    n = static_cast<double>(prism_nodes(body, s.discretisation).x.size());
    os << "  nodes: " << n << " (" << node_levels(body, s.discretisation).size()
       << " levels of nodes along z), " << 3 * n << " DOFs\n";
  }
  for (const geometry::Sphere& sphere : s.spheres)
    os << "  sphere " << sphere.name << ": radius " << sphere.radius << " at (" << sphere.center.x()
       << ", " << sphere.center.y() << ", " << sphere.center.z() << ")\n";
  for (const auto& bc : s.boundary) {
    const SolidPoints on = prism_face_points(body, s.discretisation, bc.faces, bc.box);
    double area = 0.0;
    for (double w : on.weight) area += w;
    os << "  boundary " << bc.name << ": "
       << (bc.constrains      ? "displacement"
           : bc.pressure_load ? "pressure"
                              : "traction")
       << " on area " << area;
    if (bc.box) os << box_area_text(*bc.box, on.normal);
    os << "\n";
  }
  const bool multigrid = s.linear_solver.multigrid_for(3.0 * n);
  os << "  memory: "
     << describe_bytes(n * bytes_per::solid_node(s.discretisation.method == spec::Method::Fem,
                                                  multigrid))
     << " with the " << (multigrid ? "multigrid" : "direct") << " solver, besides "
     << describe_bytes(bytes_per::program) << " for the program\n";
}

solvers::LinearSolverSettings solid_solver_settings(const spec::ProblemSpec& spec,
                                                    const SolidModel& m) {
  const spec::SolidSpec& s = spec.solid();
  solvers::LinearSolverSettings L;
  L.symmetric = (!s.discretisation.vci || s.discretisation.method == spec::Method::Fem) &&
                symmetric_tangents(spec);
  L.multigrid = s.linear_solver.multigrid_for(3.0 * m.node_count());
  if (s.discretisation.method != spec::Method::Fem)
    L.fine_smoother = solvers::LinearSolverSettings::FineSmoother::sor;
  if (L.multigrid)
    for (int I = m.own.begin; I < m.own.end; ++I)
      for (int c = 0; c < 3; ++c) L.coordinates.push_back(m.node_positions()[I](c));
  return L;
}

std::vector<Vec3> gauge_displacements(const SolidShapeTable& t, const solvers::OwnedRange& own,
                                      const std::vector<double>& d,
                                      const solvers::PetscSession& session) {
  std::vector<double> u(3 * static_cast<std::size_t>(t.rows()), 0.0);
  for (int g = 0; g < t.rows(); ++g)
    for (int k = t.offset[g]; k < t.offset[g + 1]; ++k)
      if (own.owns(t.node[k]))
        for (int c = 0; c < 3; ++c) u[3 * g + c] += t.phi[k] * d[3 * t.node[k] + c];
  solvers::sum_everywhere(session.comm(), u.data(), static_cast<int>(u.size()));
  std::vector<Vec3> out;
  for (int g = 0; g < t.rows(); ++g) out.emplace_back(u[3 * g], u[3 * g + 1], u[3 * g + 2]);
  return out;
}

} // namespace mf::implicit
