#pragma once
// Gauss-point fields carried to the nodes for output: a positive weighted average of the values
// around each node, weights phi_I(x_g)^2 w_g (positive for any shape functions, also where RK or
// serendipity functions are negative).
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <vector>

namespace mf::implicit {

/// Per node (rank 0 only; empty on the other ranks).
struct NodalAverage {
  std::vector<Vec3> stress;
  std::vector<double> stress_zz, plastic_strain, plastic;
};

/// Sums over this rank's counted points of the trial response, reduced onto rank 0.
NodalAverage nodal_average(const GalerkinModel& m, const PointStates& st,
                           const solvers::PetscSession& session);

/// The same average of an elastic solution's stresses, given at this rank's domain-table rows
/// (no plastic strain).
NodalAverage nodal_average(const GalerkinModel& m, const std::vector<Vec3>& stress,
                           const std::vector<double>& stress_zz,
                           const solvers::PetscSession& session);

} // namespace mf::implicit
