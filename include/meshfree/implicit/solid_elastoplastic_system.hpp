#pragma once
// The discrete equilibrium equations of a quasi-static elastoplastic 3D body (J2, small strain)
// on a 3D meshfree model, as the plane ones (elastoplastic_system.hpp) with 3 DOFs a node:
//   R(d) = f_int(d) + K_pen d - sum_c factor_c f_c,  f_int = sum_g w_g B^T sigma_g(eps(d), h_n),
// and the consistent tangent ([Simo & Hughes 1998] Box 3.2 through materials::stress_update_3d).
// The history at the Gauss points is committed only after an increment has converged.
#include "meshfree/implicit/incremental_system.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include <vector>

namespace mf::implicit {

/// Committed and trial material states at this rank's domain points (rows of the domain table).
struct SolidPointStates {
  std::vector<materials::MaterialState> committed, trial;
  std::vector<Vec6> committed_stress, stress; // stress of the committed history, and trial
  std::vector<Mat6> tangent;                  // trial, algorithmic
  std::vector<char> plastic;                  // trial
  std::vector<Mat6> committed_tangent;        // the tangent of the converged increment
  std::vector<char> committed_plastic;        // and whether each point was yielding in it
  explicit SolidPointStates(std::size_t n)
      : committed(n), trial(n), committed_stress(n, Vec6::Zero()), stress(n, Vec6::Zero()),
        tangent(n, Mat6::Zero()), plastic(n, 0), committed_tangent(n, Mat6::Zero()),
        committed_plastic(n, 0) {}

  /// The trial response becomes the committed one.
  void commit() {
    committed = trial, committed_stress = stress;
    committed_tangent = tangent, committed_plastic = plastic;
  }
  /// The committed response becomes the trial one again.
  void take_back() {
    trial = committed, stress = committed_stress;
    tangent = committed_tangent, plastic = committed_plastic;
  }
};

/// The J2 parameters of the body's material; a material without plasticity (an elastic preload
/// stage) gets an infinite yield stress, so that its every update is the elastic one.
materials::ConstitutiveModel solid_material_law(const spec::ProblemSpec& spec);

class SolidElastoplasticSystem : public IncrementalSystem {
public:
  /// `spec` and `m` must outlive the system.
  SolidElastoplasticSystem(const spec::ProblemSpec& spec, const SolidModel& m);
  void set_factors(const std::vector<double>& f) override { factors_ = f; }
  const std::vector<double>& factors() const { return factors_; }
  /// The trial history and stress become the committed ones; the tangent of the converged
  /// increment stays as the predictor of the next, and is taken back whenever d returns to the
  /// converged d (as in ElastoplasticSystem::commit).
  void commit() override;
  const SolidPointStates& states() const { return states_; }
  /// R(d) on the owned rows, and this rank's shares of |F|^2 and of the round-off floor of |R|^2.
  void residual(const std::vector<double>& d, double* r, solvers::ResidualSums& sums);
  /// dR/dd written in place into the matrix's values.
  void jacobian(const std::vector<double>& d, solvers::BlockValueArrays values);
  /// Every node a point of this rank touches.
  std::vector<int> needed_nodes() const;

private:
  void update_materials(const std::vector<double>& d);

  const spec::ProblemSpec& spec_;
  const SolidModel& m_;
  materials::ConstitutiveModel params_;
  SolidPointStates states_;
  BlockRows penalty_;                      // K_pen: constant
  BlockScatter scatter_;                   // where each point's blocks go among the Jacobian's
  std::vector<std::vector<double>> loads_; // per condition, then the body force: f_c at factor 1
  std::vector<char> counts_in_scale_;      // tractions and body force, not penalty right-hand sides
  std::vector<double> factors_, states_d_;
  bool states_valid_ = false;
  std::vector<double> committed_d_; // the d of the committed response; empty if not known
};

} // namespace mf::implicit
