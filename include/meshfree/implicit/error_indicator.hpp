#pragma once
// A posteriori error of a Galerkin stress field by recovery ([Zienkiewicz & Zhu 1987]): the
// stress of the solution at the Gauss points against a smoothed stress, the nodal averages
// (implicit/nodal_average) interpolated by the model's own shape functions, measured in the
// energy norm of the elastic compliance. Each Gauss point's share goes to the node whose shape
// function is largest there, so that the node's value says where the cloud is too coarse.
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <vector>

namespace mf::implicit {

struct ErrorEstimate {
  std::vector<double> node_eta2; // eta_I^2 of every node, on every rank
  double eta2 = 0.0;             // sum of eta_I^2: the estimated error squared
  double energy2 = 0.0;          // int sigma_h . C^-1 sigma_h over the body
  /// eta / sqrt(|sigma_h|^2 + eta^2), the estimated relative error in the energy norm.
  double relative() const;
};

/// The estimate for the stresses `stress` at this rank's domain-table rows, with the elastic
/// compliance `compliance` (Voigt, engineering shear). Collective.
ErrorEstimate recovery_error(const GalerkinModel& m, const std::vector<Vec3>& stress,
                             const Mat3& compliance, const solvers::PetscSession& session);

} // namespace mf::implicit
