#include "meshfree/sph/symmetry.hpp"
#include <cmath>
#include <cstddef>

namespace mf::sph {

namespace {
/// Mirrors particle k's vector and stress across the planes in `planes` (bits of s.symmetry).
void mirror_state(Hydro& s, int k, int source, int planes) {
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  const std::size_t g = static_cast<std::size_t>(k), i = static_cast<std::size_t>(source);
  for (int d = 0; d < 3; ++d) {
    P.X[3 * g + d] = P.X[3 * i + d];
    P.u[3 * g + d] = P.u[3 * i + d];
    P.v[3 * g + d] = P.v[3 * i + d];
  }
  for (int c = 0; c < 6; ++c) F.S[6 * g + c] = F.S[6 * i + c];
  // Voigt xx yy zz yz xz xy: the shear components with one index on the plane's axis flip.
  static const int shear_of[3][2] = {{4, 5}, {3, 5}, {3, 4}};
  for (std::size_t q = 0; q < s.symmetry.size(); ++q) {
    if (!(planes >> q & 1)) continue;
    const SymmetryPlane& m = s.symmetry[q];
    // The image of X + u is (2 at - X) - u.
    P.X[3 * g + m.axis] = 2.0 * m.at - P.X[3 * g + m.axis];
    P.u[3 * g + m.axis] = -P.u[3 * g + m.axis];
    P.v[3 * g + m.axis] = -P.v[3 * g + m.axis];
    F.S[6 * g + shear_of[m.axis][0]] = -F.S[6 * g + shear_of[m.axis][0]];
    F.S[6 * g + shear_of[m.axis][1]] = -F.S[6 * g + shear_of[m.axis][1]];
  }
  F.rho[g] = F.rho[i], F.e[g] = F.e[i], F.h[g] = F.h[i], F.p[g] = F.p[i], F.c[g] = F.c[i];
  F.alpha[g] = F.alpha[i], F.rho_max[g] = F.rho_max[i], F.damage[g] = F.damage[i];
  F.failed[g] = F.failed[i], F.strain_rate[g] = F.strain_rate[i];
}

} // namespace

void rebuild_mirrors(Hydro& s, double band) {
  particles::ParticleSet& P = s.particles;
  ParticleFields& F = s.fields;
  const int first = P.owned_count() + s.remote; // the first mirror image
  P.drop_ghosts_from(first);
  F.truncate(P.size());
  s.ghost_source.clear();
  s.ghost_planes.clear();
  for (std::size_t q = 0; q < s.symmetry.size(); ++q) {
    const SymmetryPlane& m = s.symmetry[q];
    const int count = P.size();
    for (int i = 0; i < count; ++i) {
      if (std::abs(P.X[3 * i + m.axis] + P.u[3 * i + m.axis] - m.at) >= band) continue;
      const int source = i < first ? i : s.ghost_source[i - first];
      const int planes = (i < first ? 0 : s.ghost_planes[i - first]) | (1 << q);
      P.add_ghost(source);
      F.append_copy(source);
      s.ghost_source.push_back(source);
      s.ghost_planes.push_back(planes);
      mirror_state(s, P.size() - 1, source, planes);
    }
  }
  group_materials(s, true);
}

void refresh_mirrors(Hydro& s) {
  const int first = s.particles.owned_count() + s.remote;
  for (std::size_t k = 0; k < s.ghost_source.size(); ++k)
    mirror_state(s, first + static_cast<int>(k), s.ghost_source[k], s.ghost_planes[k]);
}

namespace {
/// The signs a mirror particle's tensors take: component (a, b) of the source times
/// sign[a] sign[b], sign = -1 on each mirrored axis.
void mirror_signs(const Hydro& s, std::size_t ghost, double sign[3]) {
  sign[0] = sign[1] = sign[2] = 1.0;
  for (std::size_t q = 0; q < s.symmetry.size(); ++q)
    if (s.ghost_planes[ghost] >> q & 1) sign[s.symmetry[q].axis] = -sign[s.symmetry[q].axis];
}

} // namespace

void mirror_matrices(const Hydro& s, std::vector<double>& C) {
  const std::size_t first = static_cast<std::size_t>(s.particles.owned_count() + s.remote);
  for (std::size_t k = 0; k < s.ghost_source.size(); ++k) {
    double sign[3];
    mirror_signs(s, k, sign);
    const std::size_t g = 9 * (first + k), i = 9 * static_cast<std::size_t>(s.ghost_source[k]);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) C[g + 3 * a + b] = sign[a] * sign[b] * C[i + 3 * a + b];
  }
}

void mirror_voigt(const Hydro& s, std::vector<double>& T) {
  static const int rows[6] = {0, 1, 2, 1, 0, 0}, cols[6] = {0, 1, 2, 2, 2, 1};
  const std::size_t first = static_cast<std::size_t>(s.particles.owned_count() + s.remote);
  for (std::size_t k = 0; k < s.ghost_source.size(); ++k) {
    double sign[3];
    mirror_signs(s, k, sign);
    const std::size_t g = 6 * (first + k), i = 6 * static_cast<std::size_t>(s.ghost_source[k]);
    for (int c = 0; c < 6; ++c) T[g + c] = sign[rows[c]] * sign[cols[c]] * T[i + c];
  }
}

} // namespace mf::sph
