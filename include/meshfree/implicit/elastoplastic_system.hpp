#pragma once
// The discrete equilibrium equations of a quasi-static elastoplastic body (J2, plane stress or
// plane strain, small strain) on a Galerkin model, meshfree or finite elements:
//   R(d) = f_int(d) + K_pen d - sum_c factor_c f_c,   f_int = sum_g w_g B^T sigma_g(eps(d),
//   history_n),
// with f_c the traction, body-force or penalty right-hand side of condition c at factor 1, and
// their consistent tangent. The history at the Gauss points is committed only after an increment
// has converged ([Faraji 2007] incremental strategy B, section 3-1-2).
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/incremental_system.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/io/state_file.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <type_traits>
#include <vector>

namespace mf::implicit {

/// The material history and the response at this rank's domain points (the rows of the model's
/// domain table): the committed history and the stress it was committed with, and the trial
/// response of the current iterate.
struct PointStates {
  std::vector<materials::MaterialState> committed, trial;
  std::vector<Vec3> committed_stress;      // the stress of the committed history
  std::vector<double> committed_stress_zz; // its out-of-plane component
  std::vector<Vec3> stress;                // trial
  std::vector<double> stress_zz;           // trial
  std::vector<Mat3> tangent;               // trial, algorithmic
  std::vector<char> plastic;               // trial
  std::vector<Mat3> committed_tangent;     // the tangent of the converged increment
  std::vector<char> committed_plastic;     // and whether each point was yielding in it

  explicit PointStates(std::size_t n)
      : committed(n), trial(n), committed_stress(n, Vec3::Zero()), committed_stress_zz(n, 0.0),
        stress(n, Vec3::Zero()), stress_zz(n, 0.0), tangent(n, Mat3::Zero()), plastic(n, 0),
        committed_tangent(n, Mat3::Zero()), committed_plastic(n, 0) {}

  /// The trial response becomes the committed one.
  void commit() {
    committed = trial, committed_stress = stress, committed_stress_zz = stress_zz;
    committed_tangent = tangent, committed_plastic = plastic;
  }
  /// The committed response becomes the trial one again.
  void take_back() {
    trial = committed, stress = committed_stress, stress_zz = committed_stress_zz;
    tangent = committed_tangent, plastic = committed_plastic;
  }
};

class ElastoplasticSystem : public IncrementalSystem {
public:
  /// `spec` and `m` must outlive the system.
  ElastoplasticSystem(const spec::ProblemSpec& spec, const GalerkinModel& m);

  /// Load factors per boundary condition, then the body force.
  void set_factors(const std::vector<double>& f) override { factors_ = f; }
  const std::vector<double>& factors() const { return factors_; }
  const PointStates& states() const { return states_; }
  /// The law of each domain point (rows of the model's domain table).
  const PointLaws& laws() const { return laws_; }
  double residual_seconds() const { return residual_seconds_; }
  double jacobian_seconds() const { return jacobian_seconds_; }

  /// The history of the converged increment becomes the start of the next one. The trial
  /// response at the converged d stays valid: its stress is what the new history gives there
  /// too, and its tangent, the consistent tangent of the converged increment, is the predictor
  /// for the next one. Recomputed from the new history, every plastic point would sit exactly on
  /// its yield surface and round-off would choose between the elastic and the plastic tangent;
  /// so the response is kept, and taken back whenever d returns to the converged d (a solve
  /// repeated from the increment's start).
  void commit() override;

  /// Starts from a history carried here from another model of the body (a refined cloud): it
  /// becomes the committed history; the next residual returns the map from it at every point.
  void start_from(std::vector<materials::MaterialState> history);

  /// Residuals from now on are R(d) - share r0 (r0 on the owned rows, as residual() gives
  /// them): the out-of-balance r0 of a carried state taken away in steps (share 1 to 0).
  void hold_imbalance(std::vector<double> r0, double share) {
    imbalance_ = std::move(r0);
    share_ = share;
  }

  /// R(d) on the owned rows and this rank's share of the force scale |F|^2 (internal forces,
  /// tractions and body force; not the penalty right-hand sides) and of the round-off floor of
  /// |R|^2 (eps times the magnitudes of each row's internal, penalty and applied forces).
  void residual(const std::vector<double>& d, double* r, solvers::ResidualSums& sums);
  /// dR/dd as 2x2 blocks in the order of the model's block-row pattern.
  void jacobian(const std::vector<double>& d, solvers::BlockValueArrays values);

  /// This rank's share of |f_int(sigma) - f_int(sigma0)|^2 over its owned rows, sigma the stress
  /// of the last update and sigma0 the initial stress: after the equilibrium iteration of an
  /// initial stress, the out-of-balance of sigma0 with the supports' reactions at their
  /// equilibrium values (R(0) itself holds the whole reactions, which only the penalty
  /// displacements of the iteration call up).
  double initial_stress_imbalance_squared() const;

  /// Every node a point of this rank touches: the entries of d that the residual reads.
  std::vector<int> needed_nodes() const;

  /// The committed history and the response kept with it for the next increment (its first
  /// tangent is the last one's), right after commit(): a checkpoint keeps them. The trial
  /// history and stress equal the committed ones then, and are taken back from them.
  template <class Visit> void for_each_state(Visit&& visit) {
    io::visit_flat(visit, "committed", states_.committed);
    io::visit_flat(visit, "committed_stress", states_.committed_stress);
    io::visit_flat(visit, "tangent", states_.tangent);
    visit("committed_stress_zz", states_.committed_stress_zz);
    visit("plastic", states_.plastic), visit("factors", factors_);
    visit("states_d", states_d_), visit("states_valid", states_valid_);
    if constexpr (std::decay_t<Visit>::loads) {
      states_.committed_tangent = states_.tangent;
      states_.committed_plastic = states_.plastic;
      states_.take_back();
      committed_d_ = states_valid_ ? states_d_ : std::vector<double>{};
    }
  }

private:
  /// Return mapping at every point from the committed history and the strain of d. Skipped when
  /// d is the one the trial states already belong to (SNES asks for R and then J at one point),
  /// and the committed response taken back when d is the converged d of the last increment.
  void update_materials(const std::vector<double>& d);

  const spec::ProblemSpec& spec_;
  const GalerkinModel& m_;
  PointLaws laws_;
  PointStates states_;
  BlockRows penalty_;                 // K_pen: constant
  std::vector<double> penalty_force_; // K_pen d of the last residual (work array)
  BlockScatter scatter_;              // where each point's blocks go among the Jacobian's
  std::vector<std::vector<double>> loads_;
  std::vector<char> counts_in_scale_; // tractions and body force, not penalty right-hand sides
  std::vector<double> factors_;
  std::vector<double> states_d_;
  bool states_valid_ = false;
  std::vector<double> committed_d_; // the d of the committed response; empty if not known
  std::vector<double> imbalance_;   // see hold_imbalance
  double share_ = 0.0;
  double residual_seconds_ = 0.0, jacobian_seconds_ = 0.0;
};

} // namespace mf::implicit
