#include "meshfree/sph/corrections.hpp"
#include "meshfree/core/symmetric3.hpp"
#include "meshfree/sph/pair_kernel.hpp"
#include <cmath>
#include <cstddef>

namespace mf::sph {

void correction_matrices(const Hydro& s, const std::vector<double>& x, std::vector<double>& C) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const int n = P.owned_count(), dim = s.dim;
  C.assign(9 * static_cast<std::size_t>(P.size()), 0.0);
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i) {
    double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (long k = s.neighbours.pairs.offset[i]; k < s.neighbours.pairs.offset[i + 1]; ++k) {
      const int j = s.neighbours.pairs.partner[k];
      double xij[3], r2;
      const double g = pair_gradient(x, F.h, dim, s.settings.kernel, i, j, xij, r2);
      if (g == 0.0) continue;
      const double w = -P.mass[j] / F.rho[j] * g; // (x_j - x_i) = -x_ij
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) M[a][b] += w * xij[a] * xij[b];
    }
    for (int a = dim; a < 3; ++a) M[a][a] = 1.0;
    const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                       M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    double* c = &C[9 * static_cast<std::size_t>(i)];
    if (!(std::abs(det) > 1e-6)) {
      c[0] = c[4] = c[8] = 1.0;
      continue;
    }
    c[0] = (M[1][1] * M[2][2] - M[1][2] * M[2][1]) / det;
    c[1] = (M[0][2] * M[2][1] - M[0][1] * M[2][2]) / det;
    c[2] = (M[0][1] * M[1][2] - M[0][2] * M[1][1]) / det;
    c[3] = (M[1][2] * M[2][0] - M[1][0] * M[2][2]) / det;
    c[4] = (M[0][0] * M[2][2] - M[0][2] * M[2][0]) / det;
    c[5] = (M[0][2] * M[1][0] - M[0][0] * M[1][2]) / det;
    c[6] = (M[1][0] * M[2][1] - M[1][1] * M[2][0]) / det;
    c[7] = (M[0][1] * M[2][0] - M[0][0] * M[2][1]) / det;
    c[8] = (M[0][0] * M[1][1] - M[0][1] * M[1][0]) / det;
  }
}

void artificial_stresses(const Hydro& s, std::vector<double>& R) {
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const double eps = s.settings.artificial_stress;
  R.assign(6 * static_cast<std::size_t>(P.size()), 0.0);
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    if (!s.materials[m].solid()) continue;
    const int* members = s.groups.of(m);
    const int count = s.groups.owned(m);
#pragma omp parallel for schedule(static)
    for (int k = 0; k < count; ++k) {
      const int i = members[k];
      const double* si = &F.S[6 * static_cast<std::size_t>(i)];
      // The tensile part of sigma = -p I + S, in closed form (core/symmetric3.hpp): 13.5% of a
      // run with artificial stress went to an iterative eigen-solver here.
      const double sigma[6] = {si[0] - F.p[i], si[1] - F.p[i], si[2] - F.p[i], si[3], si[4], si[5]};
      double tensile[6];
      positive_part(sigma, tensile);
      const double scale = -eps / (F.rho[i] * F.rho[i]);
      double* out = &R[6 * static_cast<std::size_t>(i)];
      for (int c = 0; c < 6; ++c) out[c] = scale * tensile[c];
    }
  }
}

} // namespace mf::sph
