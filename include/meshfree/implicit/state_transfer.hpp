#pragma once
// The committed state of an elastoplastic solve carried from one model of a plane body to
// another, a cloud refined during the analysis ([Peric et al. 1996]: the history variables
// transferred between the Gauss points of the two discretisations, then equilibrium restored on
// the new one):
// - a Gauss point of the new model at the place of one of the old model keeps that point's
//   history (the cells away from the refinement are the old ones);
// - any other point takes the whole history of the nearest old point of its material (material
//   regions: never across an interface): plastic strain, back
//   stress and equivalent plastic strain of one material point together, none averaged (an
//   average over a support diffuses a plastic zone's edge; measured on Cook's membrane near its
//   limit load, the tip deflection 0.19% off where the nearest point's state gives 0.066%);
// - the nodal parameters of the new model are the projection of the old u^h on the new cloud in
//   the norm |grad v|^2 + |v|^2 / l^2 over the body (l the mean spacing), so that the new strain
//   follows the old one (a fit at the new nodes alone wiggles between them where boxes of two
//   spacings meet);
// - the stress of a point that has yielded is carried too (history_keeping_stress): its
//   plastic strain moved by the difference of the new strain there and its old point's, so that
//   its elastic strain and stress are the old point's (the new strain alone gave the strip at
//   its limit 5.8% less force after a refinement, and Cook's membrane spikes of 0.3% in its
//   force); a point that never yielded takes the stress of the new strain (a piecewise-constant
//   carried elastic stress raises the recovery estimate and drives refinement on). The return
//   map is checked at every point (ElastoplasticSystem::start_from).
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <vector>

namespace mf::implicit {

struct CarriedState {
  std::vector<double> d;                   // nodal parameters of the new model, all of them
  std::vector<materials::MaterialState> history; // per row of the new model's domain table
  long copied = 0, nearest = 0;            // the new model's points (over all ranks) by how
  std::vector<Vec3> old_strain;            // per row: the strain of the old point it came from
};

/// The carried history with the plastic strain of each point that has yielded (alpha > 0) moved
/// by the difference between the strain of the new model's parameters d there and its old
/// point's strain: the old point's elastic strain, so its stress, at the new point.
std::vector<materials::MaterialState> history_keeping_stress(const CarriedState& c,
                                                             const GalerkinModel& to,
                                                             const std::vector<double>& d);

/// Carries the committed history of `st` (this rank's rows of `from`) and the nodal parameters
/// `d` of `from` (all of them, on every rank) to the model `to` of the same body (`spec`: its
/// materials; a point takes its nearest old point of its own material). Collective.
CarriedState carry_state(const spec::ProblemSpec& spec, const GalerkinModel& from,
                         const PointStates& st, const std::vector<double>& d,
                         const GalerkinModel& to, const solvers::PetscSession& session);

} // namespace mf::implicit
