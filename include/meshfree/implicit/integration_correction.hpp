#pragma once
// Variationally consistent integration (VCI; Chen, Hillman & Rueter 2013, linear order): the
// test functions' gradients at the domain points are corrected so that the quadrature meets the
// integration constraint of linear exactness,
//   sum_g w_g grad~ Psi_I(x_g) = int_Gamma Psi_I n dGamma   for every node I,
// which the rational meshfree shape functions on background cells miss. With it the linear
// patch test passes whatever the quadrature, and a low Gauss order loses less accuracy.
#include "meshfree/implicit/galerkin_model.hpp"

namespace mf::implicit {

/// Fills m.domain_table.test_dphi with grad~ Psi_I = grad Psi_I + xi_I Psi_I, where
/// xi_I = (int_Gamma Psi_I n - sum_g w_g grad Psi_I(x_g)) / sum_g w_g Psi_I(x_g)
/// (the boundary integral over the body's whole boundary: its outline and its holes' arcs).
/// Collective: each rank corrects its own nodes and the ranks exchange the xi_I.
void correct_test_gradients(const spec::ProblemSpec& spec, GalerkinModel& m,
                            const solvers::PetscSession& session);

} // namespace mf::implicit
