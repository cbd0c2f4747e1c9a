#pragma once
// The last terms of an elastoplastic residual, plane or 3D: R = f_int + K_pen d - sum_c factor_c
// f_c over a rank's owned rows, with the sums Newton's convergence test reads (the force scale
// |F|^2 of the internal forces, tractions and body force, and the round-off floor of |R|^2).
#include "meshfree/solvers/nonlinear_system.hpp"
#include <vector>

namespace mf::implicit {

/// `r` holds f_int on its `penalty.size()` rows on entry, R on return; `loads[c]` is condition
/// c's right-hand side at factor 1 (the body force last), `in_scale[c]` whether it counts in
/// |F| (tractions and body force do, penalty right-hand sides do not).
void finish_residual(double* r, const std::vector<double>& penalty,
                     const std::vector<std::vector<double>>& loads,
                     const std::vector<double>& factors, const std::vector<char>& in_scale,
                     solvers::ResidualSums& sums);

} // namespace mf::implicit
