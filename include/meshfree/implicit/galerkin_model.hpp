#pragma once
// The solution-independent part of a Galerkin analysis (meshfree or finite elements) on one rank:
// nodes and their supports, integration points in the body and on the boundary conditions, the
// points this rank integrates with their shape functions, and the pattern of its block rows. The
// elastic solve assembles on it once, the elastoplastic solve every Newton iteration; a later
// stage evaluates a returned solution on it (shapes_at).
#include "meshfree/core/timer.hpp"
#include "meshfree/fem/elements.hpp"
#include "meshfree/fem/mesh.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/point_groups.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <memory>
#include <string>
#include <vector>

namespace mf::implicit {

/// The points a rank integrates: every point whose support holds one of its nodes, so that its
/// block rows are complete without communication (points near a partition boundary are
/// integrated by both neighbours, each keeping its own rows). `counted[k]` marks the points
/// whose lowest-numbered node it owns: sums over the body (errors, reactions) take only those,
/// so that each point counts once over all ranks.
struct RankPoints {
  std::vector<int> rows;
  std::vector<char> counted;
};

/// The points of `support` (a support list per point) that this rank integrates: those whose
/// support holds one of the nodes it owns.
RankPoints rank_points(const Csr& support, solvers::OwnedRange own, int node_count,
                       const solvers::PetscSession& session);

/// Integration points of one boundary condition, as integrated by this rank.
struct ConditionPoints {
  const spec::BoundaryCondition* bc = nullptr;
  quadrature::BoundaryPoints points; // all of the condition's points
  Csr support;                       // support lists of all of them
  RankPoints mine;
  ShapeTable table;           // rows: mine.rows (values only, no gradients)
  std::vector<double> weight; // length weight times thickness, per table row
  std::vector<Vec2> values;   // prescribed displacement or traction, per table row
};

/// A finite-element mesh and the locator that finds where a point lies in it.
struct FeDiscretisation {
  fem::Mesh mesh;
  std::unique_ptr<fem::PointLocator> locator; // points into `mesh`
};

struct GalerkinModel {
  std::unique_ptr<MeshfreeSpace> space; // meshfree nodes and supports, or
  std::unique_ptr<FeDiscretisation> fe; // a finite-element mesh
  solvers::OwnedRange own;
  quadrature::DomainPoints domain;
  Csr domain_support;
  RankPoints domain_mine;
  ShapeTable domain_table;           // rows: domain_mine.rows, with gradients
  std::vector<double> domain_weight; // area weight times thickness, per table row
  std::vector<ConditionPoints> conditions;
  RowPattern pattern;        // block rows of the owned nodes
  PointGroups domain_groups; // the domain table's rows in groups for threaded assembly
  // The volumetric strain of the cell's mean (volumetric_projection): every Gauss point of a cell
  // lies within cell_reach of any point of the cell.
  bool cell_mean = false;
  double cell_reach = 0.0;

  int node_count() const { return fe ? fe->mesh.node_count() : space->node_count(); }
  const std::vector<Vec2>& node_positions() const { return fe ? fe->mesh.x : space->nodes().x; }
};

/// Builds the model, meshfree or finite elements as the discretisation says; phases "nodes",
/// "quadrature", "neighbours" and "shape_functions" go to `timer`. Errors on any rank reach every
/// rank.
GalerkinModel build_galerkin_model(const spec::ProblemSpec& spec,
                                   const solvers::PetscSession& session, PhaseTimer& timer);

/// True for an axis-aligned rectangle without holes whose refinement boxes (if any) miss it:
/// meshed by a structured grid of square-ish elements rather than by gmsh.
bool is_plain_rectangle(const geometry::Domain& domain,
                        const std::vector<geometry::Refinement>& refinement);

/// The finite-element mesh a fem discretisation asks for: the gmsh file (checked against the
/// element type and the geometry) or a structured mesh of the rectangle; nodes numbered for
/// locality. Throws mf::Error naming the key.
fem::Mesh read_fe_mesh(const spec::ProblemSpec& spec);
/// The same for a discretisation and a plane body (a 3D prism's section).
fem::Mesh plane_fe_mesh(const spec::DiscretisationSpec& disc, const geometry::Domain& domain);

/// Cells for field output: the elements of a finite-element model, none (points) for meshfree.
io::GridCells output_cells(const GalerkinModel& m);

/// Shape functions (and gradients) of the model's approximation at arbitrary points of the body,
/// evaluated on the calling rank; with the cell-mean volumetric strain, gradients take the cell
/// of each point's nearest Gauss point (as the body's own points do).
ShapeTable shapes_at(const GalerkinModel& m, const std::vector<Vec2>& x, bool gradients);

/// The positions of this rank's domain points, in the order of the model's domain table.
std::vector<Vec2> domain_rows(const GalerkinModel& m);

/// How this model's linear systems are solved: multigrid as spec.linear_solver says (under
/// auto, from its DOF count up), with this rank's node coordinates for the rigid-body modes.
solvers::LinearSolverSettings linear_solver_settings(const spec::ProblemSpec& spec,
                                                     const GalerkinModel& m);

/// Short description of a body's discretisation for logs and the summary.
std::string describe_method(const spec::DiscretisationSpec& d, const geometry::Domain& domain);

/// Prescribed displacement or traction (force per area) at the given rows of a condition's
/// points: its value, the exact solution's, or -p n for a pressure.
std::vector<Vec2> condition_values(const spec::ProblemSpec& spec, const spec::BoundaryCondition& bc,
                                   const quadrature::BoundaryPoints& pts,
                                   const std::vector<int>& rows);

} // namespace mf::implicit
