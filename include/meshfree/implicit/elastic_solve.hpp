#pragma once
// Linear elastic static analysis on a Galerkin model (meshfree RK or MLS, or finite elements):
// one solve of K d = f, errors against an exact solution, and the fields at nodes and lines.
#include "meshfree/core/timer.hpp"
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/implicit/display_mesh.hpp"
#include "meshfree/implicit/galerkin_forms.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace mf::implicit {

struct LineSample {
  std::vector<double> s; // distance along the line
  std::vector<Vec2> x, u;
  std::vector<Vec3> stress;
};

struct ElasticResult {
  int nodes = 0, dofs = 0, domain_points = 0, boundary_points = 0, cells = 0;
  double matrix_nonzeros = 0.0, mean_support = 0.0;
  std::vector<double> parameters;                        // nodal parameters d (every rank)
  std::vector<Vec2> node_x, node_u;                      // rank 0: nodes and u^h at them
  std::vector<Vec3> node_stress;                         // rank 0
  std::vector<double> node_szz;                          // rank 0
  std::vector<std::pair<std::string, LineSample>> lines; // rank 0
  std::vector<Vec2> gauge_u;                             // rank 0: u^h at output.gauges
  std::vector<BoundaryReport> boundary;
  double error_l2 = std::numeric_limits<double>::quiet_NaN();     // relative, vs exact
  double error_energy = std::numeric_limits<double>::quiet_NaN(); // relative, vs exact
  double violation_max = 0.0, violation_relative = 0.0;
  io::GridCells output_cells; // rank 0: the elements of a finite-element model
  DisplayMesh display_mesh;   // rank 0, when asked for
  DisplayFields display;      // rank 0: u^h and the stresses at display_mesh's vertices
  solvers::SolveReport solve;
  PhaseTimer timer;
  solvers::PeakMemory memory;           // at the end of the solve
  ErrorEstimate estimate;               // when the cloud is adapted
  std::optional<Adaptation> adaptation; // the refinement passes before this solve
};

/// Solves the problem. Every rank returns the global numbers; node and line fields are filled
/// on rank 0 only, and with `display` the display mesh and its fields (for the results files).
ElasticResult solve_elastic_static(const spec::ProblemSpec& spec,
                                   const solvers::PetscSession& session, bool display = false);

} // namespace mf::implicit
