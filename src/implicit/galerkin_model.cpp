#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/fem/mesh_generation.hpp"
#include "meshfree/implicit/integration_correction.hpp"
#include "meshfree/implicit/point_coupling.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/volumetric_projection.hpp"
#include <algorithm>

namespace mf::implicit {

namespace {

/// Traction sigma . n from Voigt stress [sxx, syy, sxy].
Vec2 traction(const Vec3& s, const Vec2& n) {
  return {s(0) * n.x() + s(2) * n.y(), s(2) * n.x() + s(1) * n.y()};
}

} // namespace

RankPoints rank_points(const Csr& support, solvers::OwnedRange own, int node_count,
                       const solvers::PetscSession& s) {
  RankPoints p;
  for (int r = 0; r < support.rows(); ++r) {
    const int* first = support.index.data() + support.offset[r];
    const int* last = support.index.data() + support.offset[r + 1];
    if (std::any_of(first, last, [&](int I) { return own.owns(I); })) {
      p.rows.push_back(r);
      // support lists are sorted, so the lowest node is the first one
      p.counted.push_back(solvers::owner_of(*first, node_count, s.size()) == s.rank());
    }
  }
  return p;
}

std::vector<Vec2> condition_values(const spec::ProblemSpec& spec, const spec::BoundaryCondition& bc,
                                   const quadrature::BoundaryPoints& pts,
                                   const std::vector<int>& rows) {
  const materials::IsotropicElastic m =
      materials::plane_stress_equivalent(spec.elasticity(), spec.model);
  std::vector<Vec2> out;
  for (int r : rows) {
    if (bc.constrains)
      out.push_back(bc.value_from_exact
                        ? verification::exact_displacement(*spec.galerkin().exact, m, pts.x[r])
                        : bc.value);
    else if (bc.pressure_load)
      out.push_back(-bc.pressure * pts.normal[r]); // t = -p n, n the outward normal
    else
      out.push_back(bc.traction_from_exact
                        ? traction(verification::exact_stress(*spec.galerkin().exact, m, pts.x[r]),
                                   pts.normal[r])
                        : bc.traction);
  }
  return out;
}

namespace {

GalerkinModel build_meshfree_model(const spec::ProblemSpec& spec,
                                   const solvers::PetscSession& session, PhaseTimer& timer) {
  const spec::DiscretisationSpec& disc = spec.galerkin().discretisation;
  GalerkinModel m;
  {
    PhaseTimer::Scope scope(timer, "nodes");
    geometry::NodeCloud cloud =
        geometry::generate_nodes(spec.domain, disc.spacing, disc.refinement);
    if (disc.adapt) geometry::grade_spacing(cloud);
    m.space = std::make_unique<MeshfreeSpace>(std::move(cloud), disc.shape, disc.dilation);
    if (disc.visibility) m.space->hide_behind_holes(spec.domain);
  }
  const int N = m.node_count();
  log::info("nodes: ", N, " (", 2 * N, " DOFs), ",
            describe_method(spec.galerkin().discretisation, spec.domain));

  // Integration points: background cells over the body (refined with the nodes), Gauss points
  // on the loaded and constrained boundary pieces.
  m.conditions.resize(spec.galerkin().boundary.size());
  {
    PhaseTimer::Scope scope(timer, "quadrature");
    const quadrature::CellSizing sizing{disc.spacing, disc.refinement,
                                        disc.cell_size / disc.spacing, disc.dilation.maxCoeff()};
    m.domain = quadrature::domain_points(spec.domain, disc.cell_size, disc.order, disc.cut_levels,
                                         sizing, disc.cut_arcs);
    for (std::size_t b = 0; b < spec.galerkin().boundary.size(); ++b) {
      const spec::BoundaryCondition& bc = spec.galerkin().boundary[b];
      m.conditions[b].bc = &bc;
      m.conditions[b].points =
          quadrature::boundary_points(spec::select_boundary(spec.domain, bc.on, bc.key_path),
                                      disc.cell_size, disc.boundary_order, sizing);
    }
  }

  // Neighbours: support lists of every point, the points this rank integrates, and the exact
  // pattern of its block rows.
  m.own = solvers::owned_nodes(N, session.rank(), session.size());
  {
    PhaseTimer::Scope scope(timer, "neighbours");
    couple_points(m, session, [&](Csr support) {
      return disc.cell_mean_volumetric ? cell_supports(support, m.domain.piece) : support;
    });
  }

  // Shape functions at this rank's points, and what each point carries.
  {
    PhaseTimer::Scope scope(timer, "shape_functions");
    session.collective([&] {
      m.domain_table = m.space->shape_table(m.domain.x, m.domain_mine.rows, m.domain_support, true);
      for (auto& c : m.conditions)
        c.table = m.space->shape_table(c.points.x, c.mine.rows, c.support, false);
    });
    for (int r : m.domain_mine.rows) m.domain_weight.push_back(m.domain.weight[r] * spec.thickness);
    for (auto& c : m.conditions) {
      for (int r : c.mine.rows) c.weight.push_back(c.points.weight[r] * spec.thickness);
      c.values = condition_values(spec, *c.bc, c.points, c.mine.rows);
    }
    if (disc.vci) session.collective([&] { correct_test_gradients(spec, m, session); });
  }
  return m;
}

/// Distance from p to a boundary piece.
double distance_to(const geometry::Curve& c, const Vec2& p) {
  if (c.kind == geometry::Curve::Kind::Segment) {
    const Vec2 ab = c.b - c.a;
    const double t = std::clamp((p - c.a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    return (c.a + t * ab - p).norm();
  }
  const Vec2 r = p - c.center;
  const double lo = std::min(c.theta0, c.theta1), hi = std::max(c.theta0, c.theta1);
  const double phi = std::atan2(r.y(), r.x());
  for (double turn : {-2.0, 0.0, 2.0}) {
    const double a = phi + turn * M_PI;
    if (a >= lo && a <= hi) return std::abs(r.norm() - c.radius);
  }
  return std::min((p - c.point(0.0)).norm(), (p - c.point(1.0)).norm());
}

/// The length along boundary piece c between two of its points: the chord of a segment, the arc
/// of a circle (so that a mesh of a hole's arc covers the arc's length, whatever its chords).
double length_along(const geometry::Curve& c, const Vec2& p, const Vec2& q) {
  if (c.kind == geometry::Curve::Kind::Segment) return (q - p).norm();
  const Vec2 a = p - c.center, b = q - c.center;
  return c.radius * std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
}

} // namespace

bool is_plain_rectangle(const geometry::Domain& domain,
                        const std::vector<geometry::Refinement>& refinement) {
  const BoundingBox b = domain.bounds();
  const double area = b.size().prod();
  if (domain.vertices().size() != 4 || domain.has_arcs() || !domain.interfaces().empty() ||
      !domain.holes().empty() || !domain.outline_holes().empty() ||
      std::abs(domain.area_estimate() - area) > 1e-12 * area)
    return false;
  for (const geometry::Refinement& r : refinement)
    if ((r.box.hi.array() > b.lo.array()).all() && (r.box.lo.array() < b.hi.array()).all())
      return false;
  return true;
}

fem::Mesh read_fe_mesh(const spec::ProblemSpec& spec) {
  return plane_fe_mesh(spec.galerkin().discretisation, spec.domain);
}

fem::Mesh plane_fe_mesh(const spec::DiscretisationSpec& disc, const geometry::Domain& domain) {
  const std::string& e = disc.fem.element;
  const fem::ElementType type = e == "t3"   ? fem::ElementType::T3
                                : e == "q4" ? fem::ElementType::Q4
                                            : fem::ElementType::Q8;
  fem::Mesh mesh;
  if (disc.fem.mesh.empty() && is_plain_rectangle(domain, disc.refinement)) {
    const BoundingBox b = domain.bounds();
    const Vec2 size = b.size();
    const int nx = std::max(1, static_cast<int>(std::lround(size.x() / disc.spacing)));
    const int ny = std::max(1, static_cast<int>(std::lround(size.y() / disc.spacing)));
    mesh = fem::structured_rectangle(b.lo, size, nx, ny, type);
  } else if (disc.fem.mesh.empty()) {
    mesh = fem::mesh_domain(domain, disc.spacing, disc.refinement, type);
  } else {
    mesh = fem::read_gmsh(disc.fem.mesh);
    if (mesh.type != type)
      fail("discretisation.fem.element: '", e, "', but the mesh ", disc.fem.mesh, " holds ",
           fem::element_name(mesh.type), " elements");
    const double tol = 1e-6 * fem::characteristic_size(mesh);
    for (const Vec2& x : mesh.x)
      if (!domain.contains(x, tol))
        fail("discretisation.fem.mesh: node (", x.x(), ", ", x.y(), ") of ", disc.fem.mesh,
             " lies outside the body the geometry section describes");
  }
  fem::sort_nodes_for_locality(mesh, fem::characteristic_size(mesh));
  return mesh;
}

namespace {

/// Copies the rows `rows` of a point set's shapes into a ShapeTable.
ShapeTable table_rows(const std::vector<int>& offset, const std::vector<int>& node,
                      const std::vector<double>& phi, const std::vector<Vec2>* dphi,
                      const std::vector<int>& rows) {
  ShapeTable t;
  for (int r : rows) {
    for (int k = offset[r]; k < offset[r + 1]; ++k) {
      t.node.push_back(node[k]);
      t.phi.push_back(phi[k]);
      if (dphi) t.dphi.push_back((*dphi)[k]);
    }
    t.offset.push_back(static_cast<int>(t.node.size()));
  }
  return t;
}

/// The mesh edges on a condition's boundary pieces (all of an edge's nodes lie on one piece);
/// their length must match the pieces'.
std::vector<fem::BoundaryEdge>
edges_of_condition(const spec::ProblemSpec& spec, const spec::BoundaryCondition& bc,
                   const fem::Mesh& mesh, const std::vector<fem::BoundaryEdge>& edges, double tol) {
  const auto pieces = spec::select_boundary(spec.domain, bc.on, bc.key_path);
  std::vector<fem::BoundaryEdge> chosen;
  double length = 0.0, wanted = 0.0;
  for (const auto& piece : pieces) wanted += piece.length();
  for (const fem::BoundaryEdge& e : edges)
    for (const auto& piece : pieces) {
      bool on = true;
      for (int k = 0; k < e.count && on; ++k) on = distance_to(piece, mesh.x[e.nodes[k]]) <= tol;
      if (on) {
        chosen.push_back(e);
        length += length_along(piece, mesh.x[e.nodes[0]], mesh.x[e.nodes[1]]);
        break;
      }
    }
  if (std::abs(length - wanted) > 1e-3 * wanted)
    fail(bc.key_path, ".on: the mesh edges on the selected boundary are ", length,
         " long, the boundary pieces ", wanted,
         ": the mesh does not follow the geometry there (or a box cuts an element edge)");
  return chosen;
}

/// Gauss points of the elements and of each condition's boundary edges, with their shapes.
void place_fem_points(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                      GalerkinModel& m, fem::PointShapes& domain,
                      std::vector<fem::EdgePoints>& edge_sets) {
  const spec::DiscretisationSpec& disc = spec.galerkin().discretisation;
  const fem::Mesh& mesh = m.fe->mesh;
  const int order = default_fe_order(spec, disc, fem::default_order(mesh.type));
  session.collective([&] { domain = fem::domain_points(mesh, order); });
  m.domain.x = domain.x;
  m.domain.weight = domain.weight;
  m.domain.cell = m.domain.piece = domain.element;
  m.domain.cell_count = m.domain.piece_count = mesh.element_count();
  const std::vector<fem::BoundaryEdge> edges = fem::boundary_edges(mesh);
  const double tol = 1e-6 * fem::characteristic_size(mesh);
  const int edge_order = disc.fem.order > 0 ? disc.fem.order : fem::default_edge_order(mesh.type);
  for (std::size_t b = 0; b < spec.galerkin().boundary.size(); ++b) {
    const spec::BoundaryCondition& bc = spec.galerkin().boundary[b];
    const std::vector<fem::BoundaryEdge> chosen = edges_of_condition(spec, bc, mesh, edges, tol);
    const fem::EdgePoints& ep = edge_sets[b] = fem::edge_points(mesh, chosen, edge_order);
    ConditionPoints& c = m.conditions[b];
    c.bc = &bc;
    c.points.x = ep.x;
    c.points.weight = ep.weight;
    c.points.normal = ep.normal;
    c.support.offset = ep.offset;
    c.support.index = ep.node;
  }
}

/// The points of this rank and the sparsity pattern of the nodes they couple.
void couple_fem_nodes(const fem::PointShapes& domain, const solvers::PetscSession& session,
                      GalerkinModel& m) {
  const int N = m.node_count();
  m.domain_support.offset = domain.offset;
  m.domain_support.index = domain.node;
  std::vector<const Csr*> coupling{&m.domain_support};
  for (auto& c : m.conditions) {
    if (c.bc->constrains) coupling.push_back(&c.support);
    c.mine = rank_points(c.support, m.own, N, session);
  }
  m.domain_mine = rank_points(m.domain_support, m.own, N, session);
  m.pattern = coupling_pattern(coupling, N, m.own.begin, m.own.end);
}

/// The shape tables, weights and prescribed values of this rank's points.
void fem_shape_tables(const spec::ProblemSpec& spec, const fem::PointShapes& domain,
                      const std::vector<fem::EdgePoints>& edge_sets, GalerkinModel& m) {
  m.domain_table =
      table_rows(domain.offset, domain.node, domain.phi, &domain.dphi, m.domain_mine.rows);
  for (int r : m.domain_mine.rows) m.domain_weight.push_back(m.domain.weight[r] * spec.thickness);
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    ConditionPoints& c = m.conditions[b];
    const fem::EdgePoints& ep = edge_sets[b];
    c.table = table_rows(ep.offset, ep.node, ep.phi, nullptr, c.mine.rows);
    for (int r : c.mine.rows) c.weight.push_back(c.points.weight[r] * spec.thickness);
    c.values = condition_values(spec, *c.bc, c.points, c.mine.rows);
  }
}

GalerkinModel build_fem_model(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                              PhaseTimer& timer) {
  GalerkinModel m;
  {
    PhaseTimer::Scope scope(timer, "nodes");
    m.fe = std::make_unique<FeDiscretisation>();
    session.collective([&] { m.fe->mesh = read_fe_mesh(spec); });
    m.fe->locator = std::make_unique<fem::PointLocator>(m.fe->mesh);
  }
  const int N = m.node_count();
  log::info("nodes: ", N, " (", 2 * N, " DOFs), ",
            describe_method(spec.galerkin().discretisation, spec.domain), ", ",
            m.fe->mesh.element_count(), " elements");
  m.conditions.resize(spec.galerkin().boundary.size());
  fem::PointShapes domain;
  std::vector<fem::EdgePoints> edge_sets(spec.galerkin().boundary.size());
  {
    PhaseTimer::Scope scope(timer, "quadrature");
    place_fem_points(spec, session, m, domain, edge_sets);
  }
  m.own = solvers::owned_nodes(N, session.rank(), session.size());
  {
    PhaseTimer::Scope scope(timer, "neighbours");
    couple_fem_nodes(domain, session, m);
  }
  {
    PhaseTimer::Scope scope(timer, "shape_functions");
    fem_shape_tables(spec, domain, edge_sets, m);
  }
  return m;
}

} // namespace

GalerkinModel build_galerkin_model(const spec::ProblemSpec& spec,
                                   const solvers::PetscSession& session, PhaseTimer& timer) {
  const spec::DiscretisationSpec& disc = spec.galerkin().discretisation;
  GalerkinModel m = disc.method == spec::Method::Fem ? build_fem_model(spec, session, timer)
                                                     : build_meshfree_model(spec, session, timer);
  PhaseTimer::Scope scope(timer, "shape_functions");
  take_cell_means(m, m.domain.piece, disc);
  m.domain_groups = PointGroups(m.domain_table, domain_rows(m), m.node_positions());
  return m;
}

std::vector<Vec2> domain_rows(const GalerkinModel& m) {
  std::vector<Vec2> x;
  x.reserve(m.domain_mine.rows.size());
  for (int r : m.domain_mine.rows) x.push_back(m.domain.x[r]);
  return x;
}

solvers::LinearSolverSettings linear_solver_settings(const spec::ProblemSpec& spec,
                                                     const GalerkinModel& m) {
  solvers::LinearSolverSettings s;
  s.multigrid = spec.galerkin().linear_solver.multigrid_for(2.0 * m.node_count());
  // Corrected test functions (Petrov-Galerkin) and non-associated flow are unsymmetric.
  s.symmetric = m.domain_table.test_dphi.empty() && symmetric_tangents(spec);
  if (s.multigrid)
    for (int I = m.own.begin; I < m.own.end; ++I) {
      s.coordinates.push_back(m.node_positions()[I].x());
      s.coordinates.push_back(m.node_positions()[I].y());
    }
  return s;
}

std::string describe_method(const spec::DiscretisationSpec& d, const geometry::Domain& domain) {
  if (d.method == spec::Method::Fem) {
    std::string e = d.fem.element;
    for (char& c : e) c = static_cast<char>(std::toupper(c));
    if (!d.fem.mesh.empty()) return "FE " + e + " on " + d.fem.mesh;
    return "FE " + e +
           (is_plain_rectangle(domain, d.refinement) ? " on a structured mesh"
                                                     : " on a gmsh mesh of the geometry");
  }
  const auto& s = d.shape;
  std::string m = s.approximation == kernels::Approximation::ReproducingKernel    ? "RK"
                  : s.approximation == kernels::Approximation::MovingLeastSquares ? "MLS/EFG"
                                                                                  : "SPH";
  m += s.basis == kernels::Basis::Linear ? " Galerkin, linear basis, "
                                         : " Galerkin, quadratic basis, ";
  m += s.window.type == kernels::WindowType::CubicSpline     ? "cubic B-spline"
       : s.window.type == kernels::WindowType::QuarticSpline ? "quartic spline"
                                                             : "truncated Gaussian";
  m += s.support == kernels::SupportShape::Circular ? " window, circular supports"
                                                    : " window, rectangular supports";
  if (d.vci) m += ", VCI";
  return m;
}

io::GridCells output_cells(const GalerkinModel& m) {
  io::GridCells cells;
  if (!m.fe) return cells;
  const fem::Mesh& mesh = m.fe->mesh;
  cells.xdmf_type = mesh.type == fem::ElementType::T3   ? "Triangle"
                    : mesh.type == fem::ElementType::Q4 ? "Quadrilateral"
                                                        : "Quadrilateral_8";
  cells.nodes_per_cell = mesh.nodes_per_element();
  cells.connectivity = mesh.connectivity;
  return cells;
}

namespace {

ShapeTable plain_shapes_at(const GalerkinModel& m, const std::vector<Vec2>& x, bool gradients) {
  if (m.fe) {
    const fem::PointShapes p = fem::shapes_at(m.fe->mesh, *m.fe->locator, x, gradients);
    std::vector<int> all(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) all[i] = static_cast<int>(i);
    return table_rows(p.offset, p.node, p.phi, gradients ? &p.dphi : nullptr, all);
  }
  const Csr support = m.space->support_lists(x);
  require_covered(support, x);
  std::vector<int> all(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) all[i] = static_cast<int>(i);
  return m.space->shape_table(x, all, support, gradients);
}

} // namespace

ShapeTable shapes_at(const GalerkinModel& m, const std::vector<Vec2>& x, bool gradients) {
  ShapeTable t = plain_shapes_at(m, x, gradients);
  if (gradients && m.cell_mean)
    sample_cell_means(CellPoints<2>{m.domain.x, m.domain.weight, m.domain.piece, m.cell_reach}, x,
                      t,
                      [&m](const std::vector<Vec2>& at) { return plain_shapes_at(m, at, true); });
  return t;
}

} // namespace mf::implicit
