#pragma once
// The committed state of an elastoplastic solve carried from one model of a plane body to
// another, a cloud refined during the analysis ([Peric et al. 1996]: the history variables
// transferred between the Gauss points of the two discretisations, then equilibrium restored on
// the new one at the same load):
// - a Gauss point of the new model at the place of one of the old model keeps that point's
//   history (the cells away from the refinement are the old ones);
// - any other point takes the RK approximation of the history, sum_I phi_I(x) h_I with the old
//   model's shape functions and the nodal averages h_I (nodal_average's weights phi_I^2 w);
//   the equivalent plastic strain is kept non-negative (RK functions may be negative);
// - the nodal parameters of the new model are u^h of the old one at its nodes.
// The stress is not carried: the new model's stress is that of its strain on the carried
// history, with the return map checked (ElastoplasticSystem::start_from).
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <vector>

namespace mf::implicit {

struct CarriedState {
  std::vector<double> d;                   // nodal parameters of the new model, all of them
  std::vector<materials::J2State> history; // per row of the new model's domain table
  long copied = 0, interpolated = 0;       // the new model's points (over all ranks) by how
};

/// Carries the committed history of `st` (this rank's rows of `from`) and the nodal parameters
/// `d` of `from` (all of them, on every rank) to the model `to` of the same body. Collective.
CarriedState carry_state(const GalerkinModel& from, const PointStates& st,
                         const std::vector<double>& d, const GalerkinModel& to,
                         const solvers::PetscSession& session);

} // namespace mf::implicit
