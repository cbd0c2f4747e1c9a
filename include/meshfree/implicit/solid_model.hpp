#pragma once
// The solution-independent part of a 3D meshfree Galerkin analysis on one rank: the prism, its
// nodes and supports, the integration points of the body and of each face condition, the points
// this rank integrates with their shape functions, and the pattern of its block rows (3 DOFs a
// node). As in the plane model (galerkin_model.hpp), a rank integrates every point whose support
// holds one of its nodes, so its rows are whole without communication.
#include "meshfree/core/timer.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/point_groups.hpp"
#include "meshfree/implicit/solid_fe.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/implicit/solid_space.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace mf::implicit {

struct SolidConditionPoints {
  const spec::FaceCondition* bc = nullptr;
  SolidPoints points; // all of the condition's points
  Csr support;
  RankPoints mine;
  SolidShapeTable table;    // rows: mine.rows (values only)
  std::vector<Vec3> values; // prescribed displacement or traction at factor 1, per table row
};

struct SolidModel {
  geometry::Prism body;
  std::unique_ptr<SolidSpace> space; // meshfree nodes and supports, or
  std::unique_ptr<SolidElements> fe; // finite elements: bricks or tetrahedra
  solvers::OwnedRange own;
  SolidPoints domain;
  Csr domain_support;
  RankPoints domain_mine;
  SolidShapeTable domain_table; // rows: domain_mine.rows, with gradients
  std::vector<double> domain_weight;
  std::vector<SolidConditionPoints> conditions;
  RowPattern pattern;
  PointGroups domain_groups; // the domain table's rows in columns along z for threaded assembly
  // The volumetric strain of the cell's mean (volumetric_projection): every Gauss point of a cell
  // lies within cell_reach of any point of the cell.
  bool cell_mean = false;
  double cell_reach = 0.0;
  int node_count() const { return fe ? fe->node_count() : space->node_count(); }
  const std::vector<Vec3>& node_positions() const { return fe ? fe->nodes() : space->nodes().x; }
};

/// "meshfree RK (linear basis, spherical supports), 3D, spacing 0.5 (5 layers), dilation 2", or
/// "FE hex20 (...)" or "FE tet10 (...)", for logs and the summary.
std::string describe_solid_method(const spec::ProblemSpec& spec);

/// The sizes of a model, for the log and the summary.
struct SolidCounts {
  int nodes = 0, dofs = 0, domain_points = 0, boundary_points = 0;
  double mean_support = 0.0; // nodes per domain point
};
/// The model's counts, logged with its method.
SolidCounts count_model(const spec::ProblemSpec& spec, const SolidModel& m);

/// What a face condition does to the body: the reaction of a held face (the penalty force on
/// the body) or the load applied on a loaded one, and a held face's largest gap |u^h - ubar|.
struct FaceReport {
  std::string name;
  bool constraint = false;
  Vec3 force{0.0, 0.0, 0.0};
  double violation_max = 0.0;
  /// The face's mean displacement along its outward normal, int u^h . n dA / int dA (negative
  /// where the face moves into the body): the displacement work-conjugate to a pressure.
  double normal_displacement = 0.0;
};

/// The report of condition `c` at nodal parameters `d` (every node's) with its value scaled by
/// `factor`, summed over the ranks.
FaceReport face_report(const SolidConditionPoints& c, const std::vector<double>& d, double factor,
                       const solvers::PetscSession& session);

/// Builds the model: phases "nodes", "quadrature", "neighbours" and "shape_functions" go to
/// `timer`; with VCI the test gradients are corrected (collective). Errors on any rank reach
/// every rank.
SolidModel build_solid_model(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                             PhaseTimer& timer);

/// What `meshfree check` prints of a 3D body: nodes, layers, integration points, each face
/// condition's area, and the memory the run is expected to take.
void print_solid_plan(const spec::ProblemSpec& spec, std::ostream& os);

/// The prescribed displacement or traction (a pressure: -p n) of a face condition at factor 1
/// at the points `rows` of `pts`.
std::vector<Vec3> face_values(const spec::ProblemSpec& spec, const spec::FaceCondition& bc,
                              const SolidPoints& pts, const std::vector<int>& rows);

/// u^h at the points of table `t` (the gauges), on every rank: each rank sums its owned nodes'
/// terms (the owned entries of d are always the current ones), then the ranks add them up.
std::vector<Vec3> gauge_displacements(const SolidShapeTable& t, const solvers::OwnedRange& own,
                                      const std::vector<double>& d,
                                      const solvers::PetscSession& session);

/// u^h at every node from the nodal parameters of every node (finite elements: the parameters).
std::vector<Vec3> nodal_displacements(const SolidModel& m, const std::vector<double>& d);

/// The shape functions (and their gradients if asked) at points of the body (every node's), on
/// the calling rank; throws naming a point no node covers. With the cell-mean volumetric strain,
/// rows with gradients carry it too (the cell of the point's nearest Gauss point), so that
/// passive points (output samples, a stage's particles) are strained as the Gauss points are.
SolidShapeTable solid_shapes_at(const SolidModel& m, const std::vector<Vec3>& x,
                                bool gradients = false);

/// How the model's linear systems are solved (direct, or multigrid with the six rigid-body modes
/// from the owned nodes' coordinates), as spec.solid().linear_solver says.
solvers::LinearSolverSettings solid_solver_settings(const spec::ProblemSpec& spec,
                                                    const SolidModel& m);

} // namespace mf::implicit
