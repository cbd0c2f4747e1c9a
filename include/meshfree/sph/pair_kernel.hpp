#pragma once
// The kernel gradient of a particle pair, shared by the rate loops.
#include "meshfree/kernels/sph_kernel.hpp"
#include <cmath>
#include <vector>

namespace mf::sph {

/// grad_i W_ij / r_ij for a pair within the support of h_bar, or 0; x_ij between the current
/// positions x (X + u, 3 per particle, gathered once per rate evaluation so that the pair loops
/// stream one array), h the smoothing lengths.
inline double pair_gradient(const std::vector<double>& x, const std::vector<double>& h, int dim,
                            kernels::SphKernel kernel, int i, int j, double xij[3], double& r2) {
  r2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    xij[d] = x[3 * i + d] - x[3 * j + d];
    r2 += xij[d] * xij[d];
  }
  const double hij = 0.5 * (h[i] + h[j]);
  if (r2 >= 4.0 * hij * hij || r2 == 0.0) return 0.0;
  const double rr = std::sqrt(r2);
  return kernels::sph_kernel_slope_over_r(kernel, dim, rr, hij);
}

} // namespace mf::sph
