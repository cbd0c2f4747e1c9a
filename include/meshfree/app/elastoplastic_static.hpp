#pragma once
// Quasi-static elastoplastic analysis (J2, plane stress or plane strain, small strain) on the
// same Galerkin model as the elastic solver, meshfree or finite elements:
//   R(d) = f_int(d) + K_pen d - lambda_c f_c = 0,   f_int = sum_g w_g B^T sigma_g(eps(d),
//   history_n),
// solved increment by increment with Newton through PETSc SNES and the consistent tangent. The
// history at the Gauss points is committed only after an increment has converged (the thesis'
// incremental strategy B, section 3-1-2); increments that do not converge are halved and retried.
#include "meshfree/app/galerkin_model.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <limits>
#include <string>
#include <vector>

namespace mf::app {

/// One converged increment.
struct IncrementRecord {
  int step = 0;                // index into ProblemSpec::steps
  double step_fraction = 0.0;  // how far through the step, in (0, 1]
  std::vector<double> factors; // per boundary condition, then the body force
  solvers::NewtonReport newton;
  int cutbacks = 0; // halvings of this increment before it converged
  std::vector<BoundaryReport> boundary;
  std::vector<Vec2> monitor_u; // u^h at the monitor points
  double max_plastic_strain = 0.0;
  long plastic_points = 0;
  double equilibrium_error = 0.0; // |sum of reactions and loads| / sum of their magnitudes
};

/// The largest von Mises stress of the elastic solution at the end of the first step, over one
/// kind of point.
struct PeakStress {
  double von_mises = 0.0;
  Vec2 at{0.0, 0.0};
  double fraction = std::numeric_limits<double>::infinity(); // sigma_y0 / von_mises
};

/// First yield under the first step's loading, from a linear elastic solve (loads are
/// proportional within a step, so the elastic stresses scale with the load factor). First yield
/// is where the stress at a node reaches sigma_y0: nodes lie inside the body and on its
/// boundary, where stress concentrations peak. The peak over the Gauss points, which lie inside
/// and near the boundary are the least accurate points of a meshfree stress field, is reported
/// beside it.
struct ElasticLimit {
  PeakStress gauss_points, nodes;
  double fraction = std::numeric_limits<double>::quiet_NaN(); // of the first step's targets
  std::vector<double> factors;                                // at first yield
  std::vector<BoundaryReport> boundary;                       // reactions and loads there
};

struct ElastoplasticResult {
  std::string method, solver;
  int nodes = 0, dofs = 0, domain_points = 0, boundary_points = 0, cells = 0;
  double matrix_nonzeros = 0.0;
  std::vector<IncrementRecord> increments; // increment 0 is the unloaded state
  ElasticLimit elastic_limit;
  std::string status = "completed"; // or "stopped", with the reason
  std::string stop_reason;
  std::vector<std::pair<std::string, std::vector<std::vector<double>>>> lines; // rank 0 rows
  PhaseTimer timer;
  double residual_seconds = 0.0, jacobian_seconds = 0.0; // inside the "newton" phase
};

/// Runs the load schedule. Fields go to `out` (rank 0; null on other ranks or to skip them) as
/// the run goes. A run whose increment cannot converge even after the allowed cut-backs stops
/// with status "stopped", keeping the converged increments.
ElastoplasticResult solve_elastoplastic_static(const io::ProblemSpec& spec,
                                               const solvers::PetscSession& session,
                                               io::OutputDirectory* out);

/// Writes history.csv, line_*.csv and summary.json (rank 0).
void write_elastoplastic_outputs(const io::ProblemSpec& spec, const ElastoplasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out);

} // namespace mf::app
