#pragma once
// Corrections of the SPH rates: the kernel-gradient correction matrices and the artificial
// stress against the tensile instability of solids.
#include "meshfree/sph/hydro.hpp"
#include <vector>

namespace mf::sph {

/// Kernel-gradient correction (Bonet & Lok 1999; Randles & Libersky 1996): per particle the
/// inverse of M_i = sum_j V_j (x_j - x_i) (x) grad_i W_ij, so that the corrected gradient
/// M_i^-1 grad_i W_ij reproduces the gradient of any linear field exactly, near free surfaces
/// too. Unused axes keep 1 on the diagonal; a particle with too few neighbours to invert M keeps
/// the uncorrected kernel (identity).
/// x: the current positions (X + u), 3 per particle.
void correction_matrices(const Hydro& s, const std::vector<double>& x, std::vector<double>& C);

/// The artificial stress of every solid particle: R = Q diag(R_a) Q^T with
/// R_a = -epsilon sigma_a / rho^2 for each tensile principal stress sigma_a of sigma = -p I + S
/// (Gray, Monaghan & Swift 2001, eqs. 3.11-3.13), 0 for compressive ones.
void artificial_stresses(const Hydro& s, std::vector<double>& R);

} // namespace mf::sph
