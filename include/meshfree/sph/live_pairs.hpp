#pragma once
// The pairs of a neighbour-list row that interact now (r < 2 h_ij, r > 0), selected for the rate
// passes of sph/pair_sums.cpp with their kernel slopes, and the arrays those passes fill for
// them, one array per quantity so that the pair arithmetic runs as packed loops. The selection is
// compiled for the baseline and for AVX2 (core/simd_target.hpp: four pairs at a time, kept ones
// packed to the front by a lane permutation); both keep the same pairs, in the row's order, with
// the same values bit for bit.
#include "meshfree/core/simd_target.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/neighbors/pair_list.hpp"
#include <cstddef>
#include <vector>

namespace mf::sph {

/// A row's interacting pairs and their terms.
struct LivePairs {
  std::vector<int> j;
  std::vector<double> x[3], r2, h, g; // x_i - x_j, r^2, h_ij, grad_i W_ij / r_ij
  std::vector<double> v[3];           // v_i - v_j
  std::vector<double> m, vol;         // m_j, m_j / rho_j
  std::vector<double> c, rho;         // c_j, rho_j
  std::vector<double> q;              // p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij
  std::vector<double> T[6];           // S_i / rho_i^2 + S_j / rho_j^2 (+ artificial stress)
  std::vector<double> gv[3];          // the pair's kernel gradient
  std::vector<double> gi[3], gj[3];   // C_i g x_ij and C_j g x_ij (with the correction)
  std::vector<double> f[3];           // q gv - T gv: the momentum term per m_i m_j
  std::vector<double> vg, w;          // v_ij . gv and q v_ij . gv - v_ij . T gv
  std::vector<double> push;           // inter-material penalty force / r (0: none)
  /// Room for a row of n pairs.
  void reserve(std::size_t n);
};

/// The interacting pairs of row i of `list` (r^2 < 4 h_ij^2 with h_ij = (h_i + h_j) / 2, r^2 != 0),
/// in the row's order: their partners j, x_i - x_j over the model's `dim` axes, r^2, h_ij and
/// the kernel's slope over r, g,
/// from xh (x, y, z and h per particle; coordinates beyond dim are zero for every particle, so
/// their terms, exact zeros, are left out): the test and the values of pair_gradient
/// (sph/pair_kernel.hpp), so every rate loop sums the same terms. Returns their count. Every
/// target gives the same.
int select_live_pairs(int dim, const neighbors::PairList& list, const double* xh, int i,
                      kernels::SphKernel kernel, LivePairs& live, SimdTarget target);

} // namespace mf::sph
