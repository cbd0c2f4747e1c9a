#pragma once
// What a quasi-static elastoplastic analysis returns: the record of every converged increment,
// first yield, and the converged state itself (model, nodal parameters and the history of every
// Gauss point), from which a later stage can evaluate the solution anywhere in the body.
#include "meshfree/core/timer.hpp"
#include "meshfree/implicit/adaptivity.hpp"
#include "meshfree/implicit/elastic_limit.hpp"
#include "meshfree/implicit/galerkin_forms.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mf::implicit {

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
  // With ProblemSpec::record_increment_parameters: the nodal parameters d of the increment, all
  // 2N of them, on every rank (increment 0: zeros); empty otherwise.
  std::vector<double> parameters;

  /// Every member by name (a checkpoint keeps the increments so far).
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("step", step), visit("step_fraction", step_fraction), visit("factors", factors);
    visit("newton.converged", newton.converged), visit("newton.iterations", newton.iterations);
    visit("newton.linear_iterations", newton.linear_iterations);
    visit("newton.linear_iterations_max", newton.linear_iterations_max);
    visit("newton.tangents", newton.tangents);
    visit("newton.reason", newton.reason), visit("newton.failure", newton.failure);
    visit("newton.residual", newton.residual), visit("newton.scale", newton.scale);
    visit("cutbacks", cutbacks), visit("max_plastic_strain", max_plastic_strain);
    visit("plastic_points", plastic_points), visit("equilibrium_error", equilibrium_error);
    visit("parameters", parameters);
    io::visit_flat(visit, "monitor_u", monitor_u);
    io::visit_list(visit, "boundary", boundary, [](const auto& at, BoundaryReport& b) {
      at("name", b.name), at("constraint", b.constraint), at("force", b.force);
      at("violation_max", b.violation_max);
    });
  }
};

/// The last converged state. Gauss-point arrays run over this rank's domain points, in the order
/// of the model's domain table: row k is the point model->domain.x[model->domain_mine.rows[k]]
/// (points near a partition boundary appear on both neighbouring ranks;
/// model->domain_mine.counted marks the copy that counts).
struct ElastoplasticState {
  std::shared_ptr<const GalerkinModel> model;
  std::vector<double> parameters;          // nodal parameters d, all 2N of them, on every rank
  std::vector<double> factors;             // load factors per condition, then the body force
  std::vector<materials::MaterialState> history; // plastic strain, back stress, alpha per point
  std::vector<Vec3> stress;                // [sxx, syy, sxy] per point
  std::vector<double> stress_zz;           // per point
};

struct ElastoplasticResult {
  std::string method, solver;
  int nodes = 0, dofs = 0, domain_points = 0, boundary_points = 0, cells = 0;
  double matrix_nonzeros = 0.0;
  std::vector<IncrementRecord> increments; // increment 0 is the unloaded state
  ElasticLimit elastic_limit;
  // With an initial stress: its out-of-balance, |f_int(sigma0) + K_pen d_1 - f_ext| / |F| after
  // the equilibrium step d_1 (the reactions at their equilibrium values), which equals
  // |f_int(sigma_1) - f_int(sigma0)| / |F|: the load the equilibrium iteration carried by
  // deforming. R(0) itself holds the whole support reactions.
  double initial_out_of_balance = std::numeric_limits<double>::quiet_NaN();
  ElastoplasticState state;
  std::string status = "completed"; // or "stopped", with the reason
  std::string stop_reason;
  std::vector<std::pair<std::string, std::vector<std::vector<double>>>> lines; // rank 0 rows
  io::CheckpointCounts checkpoints; // one after every converged increment, with an output folder
  PhaseTimer timer;
  solvers::PeakMemory memory;                            // at the end of the solve
  double residual_seconds = 0.0, jacobian_seconds = 0.0; // inside the "newton" phase
  ErrorEstimate estimate;               // of the final state, when the cloud is adapted
  std::optional<Adaptation> adaptation; // the refinement passes before this solve
};

} // namespace mf::implicit
