#include "meshfree/sph/hydro.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/kernels/sph_kernel.hpp"
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mf::sph {

materials::PressureAndSound evaluate(const Material& m, double rho, double e, double rho_max,
                                     double damage) {
  const Eos& eos = m.eos;
  switch (eos.kind) {
  case Eos::Kind::IdealGas:
    return materials::ideal_gas(eos.ideal_gas, rho, e);
  case Eos::Kind::Jwl:
    return materials::jwl(eos.jwl, rho, e);
  case Eos::Kind::MieGruneisen:
    return materials::mie_gruneisen(eos.mie_gruneisen, rho, e);
  case Eos::Kind::LinearPolynomial:
    return materials::linear_polynomial(eos.linear_polynomial, rho, e);
  case Eos::Kind::Compaction:
    return materials::compaction(eos.compaction, rho, rho_max);
  case Eos::Kind::Hjc:
    return materials::hjc_pressure(m.hjc, rho, rho_max, damage);
  }
  return {};
}

double shear_modulus(const Material& m, double rho) {
  const Strength& st = m.strength;
  if (st.model == Strength::Model::Granular && !st.granular.shear_modulus.x.empty())
    return st.granular.shear_modulus(rho);
  return st.shear_modulus;
}

double current_yield(const Material& m, double pressure, double alpha, double damage,
                     double strain_rate) {
  const Strength& st = m.strength;
  switch (st.model) {
  case Strength::Model::Elastic:
    return 0.0;
  case Strength::Model::VonMises:
    return materials::yield_stress(st.yield, alpha);
  case Strength::Model::Granular:
    return materials::granular_yield(st.granular, pressure);
  case Strength::Model::Hjc:
    return materials::hjc_yield(m.hjc, pressure, damage, strain_rate);
  }
  return 0.0;
}

void Particles::add(const double position[3], double m, double density, double energy,
                    double smoothing, int mat, bool is_fixed) {
  for (int d = 0; d < 3; ++d) {
    x.push_back(position[d]);
    v.push_back(0.0);
  }
  mass.push_back(m);
  rho.push_back(density);
  e.push_back(energy);
  h.push_back(smoothing);
  rho_ref.push_back(density);
  h_ref.push_back(smoothing);
  material.push_back(mat);
  light_time.push_back(-1.0);
  fixed.push_back(is_fixed ? 1 : 0);
  for (int k = 0; k < 6; ++k) S.push_back(0.0);
  alpha.push_back(0.0);
  rho_max.push_back(density);
  damage.push_back(0.0);
  strain_rate.push_back(0.0);
  failed.push_back(0);
  p.push_back(0.0);
  c.push_back(0.0);
}

void Particles::append_copy(int i) {
  const std::size_t k = static_cast<std::size_t>(i);
  const auto copy = [k](auto& a, std::size_t per) {
    for (std::size_t c = 0; c < per; ++c) {
      const auto value = a[per * k + c];
      a.push_back(value);
    }
  };
  copy(x, 3), copy(v, 3), copy(S, 6);
  for (auto* a : {&mass, &rho, &e, &h, &rho_ref, &h_ref, &light_time, &alpha, &rho_max, &damage,
                  &strain_rate, &p, &c})
    copy(*a, 1);
  copy(material, 1), copy(failed, 1);
  fixed.push_back(1);
}

void Particles::truncate(int n) {
  const std::size_t m = static_cast<std::size_t>(n);
  x.resize(3 * m), v.resize(3 * m), S.resize(6 * m);
  for (auto* a : {&mass, &rho, &e, &h, &rho_ref, &h_ref, &light_time, &alpha, &rho_max, &damage,
                  &strain_rate, &p, &c})
    a->resize(m);
  material.resize(m), fixed.resize(m), failed.resize(m);
}

namespace {
/// Mirrors particle k's vector and stress across the planes in `planes` (bits of s.symmetry).
void mirror_state(Hydro& s, int k, int source, int planes) {
  Particles& P = s.particles;
  const std::size_t g = static_cast<std::size_t>(k), i = static_cast<std::size_t>(source);
  for (int d = 0; d < 3; ++d) {
    P.x[3 * g + d] = P.x[3 * i + d];
    P.v[3 * g + d] = P.v[3 * i + d];
  }
  for (int c = 0; c < 6; ++c) P.S[6 * g + c] = P.S[6 * i + c];
  // Voigt xx yy zz yz xz xy: the shear components with one index on the plane's axis flip.
  static const int shear_of[3][2] = {{4, 5}, {3, 5}, {3, 4}};
  for (std::size_t q = 0; q < s.symmetry.size(); ++q) {
    if (!(planes >> q & 1)) continue;
    const SymmetryPlane& m = s.symmetry[q];
    P.x[3 * g + m.axis] = 2.0 * m.at - P.x[3 * g + m.axis];
    P.v[3 * g + m.axis] = -P.v[3 * g + m.axis];
    P.S[6 * g + shear_of[m.axis][0]] = -P.S[6 * g + shear_of[m.axis][0]];
    P.S[6 * g + shear_of[m.axis][1]] = -P.S[6 * g + shear_of[m.axis][1]];
  }
  P.rho[g] = P.rho[i], P.e[g] = P.e[i], P.h[g] = P.h[i], P.p[g] = P.p[i], P.c[g] = P.c[i];
  P.alpha[g] = P.alpha[i], P.rho_max[g] = P.rho_max[i], P.damage[g] = P.damage[i];
  P.failed[g] = P.failed[i], P.strain_rate[g] = P.strain_rate[i];
}

/// Drops the old mirror particles and mirrors every particle within `band` of each plane, the
/// images of earlier planes included (corners of two or three planes).
void rebuild_ghosts(Hydro& s, double band) {
  Particles& P = s.particles;
  if (s.real < 0) s.real = P.size();
  P.truncate(s.real);
  s.ghost_of.clear();
  s.ghost_planes.clear();
  for (std::size_t q = 0; q < s.symmetry.size(); ++q) {
    const SymmetryPlane& m = s.symmetry[q];
    const int count = P.size();
    for (int i = 0; i < count; ++i) {
      if (std::abs(P.x[3 * i + m.axis] - m.at) >= band) continue;
      const int source = i < s.real ? i : s.ghost_of[i - s.real];
      const int planes = (i < s.real ? 0 : s.ghost_planes[i - s.real]) | (1 << q);
      P.append_copy(source);
      s.ghost_of.push_back(source);
      s.ghost_planes.push_back(planes);
      mirror_state(s, P.size() - 1, source, planes);
    }
  }
}
} // namespace

void refresh_ghosts(Hydro& s) {
  for (std::size_t k = 0; k < s.ghost_of.size(); ++k)
    mirror_state(s, s.real + static_cast<int>(k), s.ghost_of[k], s.ghost_planes[k]);
}

namespace {
/// Lights every explosive particle at distance(x) / D_CJ; with an unreacted equation of state
/// only a booster of 2 h is lit on schedule, and the shock lights the rest (update_state).
template <class Distance> void light_by_distance(Hydro& s, Distance distance) {
  Particles& P = s.particles;
  for (int i = 0; i < P.size(); ++i) {
    const Eos& eos = s.materials[P.material[i]].eos;
    if (eos.kind != Eos::Kind::Jwl) continue;
    const double r = distance(&P.x[3 * static_cast<std::size_t>(i)]);
    if (eos.has_unreacted && r > 2.0 * P.h[i]) continue;
    P.light_time[i] = r / eos.jwl.detonation_speed;
  }
}
} // namespace

void light_from_point(Hydro& s, const double at[3]) {
  light_by_distance(s, [at](const double* x) {
    return std::sqrt((x[0] - at[0]) * (x[0] - at[0]) + (x[1] - at[1]) * (x[1] - at[1]) +
                     (x[2] - at[2]) * (x[2] - at[2]));
  });
}

void light_from_plane(Hydro& s, const double at[3], const double normal[3]) {
  light_by_distance(s, [at, normal](const double* x) {
    return std::abs((x[0] - at[0]) * normal[0] + (x[1] - at[1]) * normal[1] +
                    (x[2] - at[2]) * normal[2]);
  });
}

void update_state(Hydro& s) {
  Particles& P = s.particles;
  const int n = P.size();
  const double inv_dim = 1.0 / P.dim;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.h[i] = P.h_ref[i] * std::pow(P.rho_ref[i] / P.rho[i], inv_dim);
    const Material& mat = s.materials[P.material[i]];
    const Eos& eos = mat.eos;
    const materials::PressureAndSound ps =
        evaluate(mat, P.rho[i], P.e[i], P.rho_max[i], P.damage[i]);
    double f = 1.0;
    if (eos.kind == Eos::Kind::Jwl && eos.has_unreacted && P.light_time[i] < 0.0 &&
        P.rho[i] >= (1.0 + s.settings.ignition_compression) * eos.jwl.rho0)
      P.light_time[i] = s.time;
    if (eos.kind == Eos::Kind::Jwl && P.light_time[i] >= 0.0) {
      // Burn fraction F = max(F_programmed, F_beta) (Wilkins 1964; LS-DYNA's
      // *MAT_HIGH_EXPLOSIVE_BURN): the lit time over the burn width, or the compression toward
      // the CJ state, (1 - V) / (1 - V_CJ) with 1 - V_CJ = P_CJ / (rho0 D^2).
      const materials::Jwl& j = eos.jwl;
      const double programmed =
          (s.time - P.light_time[i]) * j.detonation_speed / (s.settings.burn_width * P.h[i]);
      const double beta = (1.0 - j.rho0 / P.rho[i]) * j.rho0 * j.detonation_speed *
                          j.detonation_speed / j.cj_pressure;
      // With an unreacted equation of state the shock has compressed the particle before it
      // lights, and the burn follows its lighting time only (a ZND front).
      f = std::clamp(eos.has_unreacted ? programmed : std::max(programmed, beta), 0.0, 1.0);
    } else if (eos.kind == Eos::Kind::Jwl) {
      f = 0.0; // never lit: inert
    }
    double pressure = f * ps.p, c2 = ps.c2;
    if (eos.kind == Eos::Kind::Jwl && eos.has_unreacted) {
      // The unreacted share follows its own Hugoniot, with the energy gained above the initial
      // state (e - e0): a shock into the explosive (the von Neumann spike), then the burn.
      const materials::PressureAndSound u =
          materials::mie_gruneisen(eos.unreacted, P.rho[i], P.e[i] - eos.jwl.e0);
      pressure += (1.0 - f) * u.p;
      c2 = std::max(c2, u.c2);
    }
    P.p[i] = P.failed[i] ? std::max(pressure, 0.0) : pressure;
    // The unburnt explosive keeps the products' sound speed so that the step resolves the burn;
    // a solid's longitudinal speed adds 4G / (3 rho).
    const double shear =
        mat.strength.enabled ? 4.0 * shear_modulus(mat, P.rho[i]) / (3.0 * P.rho[i]) : 0.0;
    P.c[i] = std::sqrt(std::max(c2, 0.0) + shear);
  }
}

void refresh_neighbours(Hydro& s) {
  const Particles& P = s.particles;
  const int n = P.size();
  const double skin = s.settings.skin;
  // A pair (i, j) left out at the last build was at least (h_i + h_j)(1 + skin) apart then; it
  // cannot interact yet while every particle has moved and grown its h by less than skin h.
  if (!s.x_at_build.empty()) {
    bool stale = false;
#pragma omp parallel for schedule(static) reduction(|| : stale)
    for (int i = 0; i < n; ++i) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double dx = P.x[3 * i + k] - s.x_at_build[3 * i + k];
        d2 += dx * dx;
      }
      const double grown = std::max(0.0, P.h[i] - s.h_at_build[i]);
      if (std::sqrt(d2) + grown > skin * s.h_at_build[i]) stale = true;
    }
    if (!stale) return;
  }
  const double h_max = *std::max_element(P.h.begin(), P.h.begin() + s.real_count());
  s.build_radius = 2.0 * h_max * (1.0 + skin);
  if (!s.symmetry.empty()) rebuild_ghosts(s, s.build_radius);
  const neighbors::PairList all = neighbors::pairs_within(P.x, s.build_radius);
  // Keep the pairs within (h_i + h_j)(1 + skin): with smoothing lengths that differ across the
  // body, the global radius would hand small particles many far partners.
  const int with_ghosts = P.size();
  s.pairs.offset.assign(with_ghosts + 1, 0);
  s.pairs.partner.clear();
  for (int i = 0; i < with_ghosts; ++i) {
    for (long k = all.offset[i]; k < all.offset[i + 1]; ++k) {
      const int j = all.partner[k];
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double dx = P.x[3 * i + d] - P.x[3 * j + d];
        r2 += dx * dx;
      }
      const double reach = (P.h[i] + P.h[j]) * (1.0 + skin);
      if (r2 < reach * reach) s.pairs.partner.push_back(j);
    }
    s.pairs.offset[i + 1] = static_cast<long>(s.pairs.partner.size());
  }
  s.x_at_build = P.x;
  s.h_at_build = P.h;
  ++s.rebuilds;
}

namespace {
bool any_solid(const Hydro& s) {
  for (const Material& m : s.materials)
    if (m.strength.enabled) return true;
  return false;
}

/// The dashpot force of particle k of a transmitting boundary at velocity v.
inline void boundary_force(const TransmittingBoundary& b, std::size_t k, const double* v,
                           double f[3]) {
  const double vn = v[0] * b.normal[0] + v[1] * b.normal[1] + v[2] * b.normal[2];
  for (int d = 0; d < 3; ++d) {
    const double normal_part = vn * b.normal[d];
    f[d] = -b.area[k] *
           (b.normal_impedance[k] * normal_part + b.shear_impedance[k] * (v[d] - normal_part));
  }
}

/// grad_i W_ij / r_ij for a pair within the support of h_bar, or 0.
inline double pair_gradient(const Particles& P, int dim, kernels::SphKernel kernel, int i, int j,
                            double xij[3], double& r2) {
  r2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    xij[d] = P.x[3 * i + d] - P.x[3 * j + d];
    r2 += xij[d] * xij[d];
  }
  const double hij = 0.5 * (P.h[i] + P.h[j]);
  if (r2 >= 4.0 * hij * hij || r2 == 0.0) return 0.0;
  const double rr = std::sqrt(r2);
  return kernels::sph_kernel_slope(kernel, dim, rr, hij) / rr;
}
} // namespace

namespace {
/// The signs a mirror particle's tensors take: component (a, b) of the source times
/// sign[a] sign[b], sign = -1 on each mirrored axis.
void mirror_signs(const Hydro& s, std::size_t ghost, double sign[3]) {
  sign[0] = sign[1] = sign[2] = 1.0;
  for (std::size_t q = 0; q < s.symmetry.size(); ++q)
    if (s.ghost_planes[ghost] >> q & 1) sign[s.symmetry[q].axis] = -sign[s.symmetry[q].axis];
}

/// Fills the mirror particles' correction matrices (9 per particle) from their sources.
void mirror_matrices(const Hydro& s, std::vector<double>& C) {
  for (std::size_t k = 0; k < s.ghost_of.size(); ++k) {
    double sign[3];
    mirror_signs(s, k, sign);
    const std::size_t g = 9 * (s.real + k), i = 9 * static_cast<std::size_t>(s.ghost_of[k]);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) C[g + 3 * a + b] = sign[a] * sign[b] * C[i + 3 * a + b];
  }
}

/// Fills the mirror particles' symmetric tensors (6 per particle, Voigt) from their sources.
void mirror_voigt(const Hydro& s, std::vector<double>& T) {
  static const int rows[6] = {0, 1, 2, 1, 0, 0}, cols[6] = {0, 1, 2, 2, 2, 1};
  for (std::size_t k = 0; k < s.ghost_of.size(); ++k) {
    double sign[3];
    mirror_signs(s, k, sign);
    const std::size_t g = 6 * (s.real + k), i = 6 * static_cast<std::size_t>(s.ghost_of[k]);
    for (int c = 0; c < 6; ++c) T[g + c] = sign[rows[c]] * sign[cols[c]] * T[i + c];
  }
}

/// Kernel-gradient correction (Bonet & Lok 1999; Randles & Libersky 1996): per particle the
/// inverse of M_i = sum_j V_j (x_j - x_i) (x) grad_i W_ij, so that the corrected gradient
/// M_i^-1 grad_i W_ij reproduces the gradient of any linear field exactly, near free surfaces
/// too. Unused axes keep 1 on the diagonal; a particle with too few neighbours to invert M keeps
/// the uncorrected kernel (identity).
void correction_matrices(const Hydro& s, std::vector<double>& C) {
  const Particles& P = s.particles;
  const int n = s.real_count(), dim = P.dim;
  C.assign(9 * static_cast<std::size_t>(P.size()), 0.0);
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i) {
    double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (long k = s.pairs.offset[i]; k < s.pairs.offset[i + 1]; ++k) {
      const int j = s.pairs.partner[k];
      double xij[3], r2;
      const double g = pair_gradient(P, dim, s.settings.kernel, i, j, xij, r2);
      if (g == 0.0) continue;
      const double w = -P.mass[j] / P.rho[j] * g; // (x_j - x_i) = -x_ij
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

/// The artificial stress of every solid particle: R = Q diag(R_a) Q^T with
/// R_a = -epsilon sigma_a / rho^2 for each tensile principal stress sigma_a of sigma = -p I + S
/// (Gray, Monaghan & Swift 2001, eqs. 3.11-3.13), 0 for compressive ones.
void artificial_stresses(const Hydro& s, std::vector<double>& R) {
  const Particles& P = s.particles;
  const int n = s.real_count();
  const double eps = s.settings.artificial_stress;
  R.assign(6 * static_cast<std::size_t>(P.size()), 0.0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    if (!s.materials[P.material[i]].strength.enabled) continue;
    const double* si = &P.S[6 * static_cast<std::size_t>(i)];
    Eigen::Matrix3d sigma;
    sigma << si[0] - P.p[i], si[5], si[4], si[5], si[1] - P.p[i], si[3], si[4], si[3],
        si[2] - P.p[i];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sigma);
    Eigen::Vector3d ra = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a)
      if (eig.eigenvalues()[a] > 0.0) ra[a] = -eps * eig.eigenvalues()[a] / (P.rho[i] * P.rho[i]);
    const Eigen::Matrix3d Ri =
        eig.eigenvectors() * ra.asDiagonal() * eig.eigenvectors().transpose();
    double* out = &R[6 * static_cast<std::size_t>(i)];
    out[0] = Ri(0, 0), out[1] = Ri(1, 1), out[2] = Ri(2, 2);
    out[3] = Ri(1, 2), out[4] = Ri(0, 2), out[5] = Ri(0, 1);
  }
}

/// The kernel gradient of a pair as a vector: g x_ij, or with the correction A g x_ij for the
/// 3x3 matrix A (row-major).
inline void gradient_vector(const double* A, double g, const double xij[3], double out[3]) {
  if (!A) {
    for (int d = 0; d < 3; ++d) out[d] = g * xij[d];
    return;
  }
  for (int a = 0; a < 3; ++a)
    out[a] = g * (A[3 * a] * xij[0] + A[3 * a + 1] * xij[1] + A[3 * a + 2] * xij[2]);
}
} // namespace

void compute_rates(const Hydro& s, Rates& r) {
  const Particles& P = s.particles;
  const Settings& S = s.settings;
  // Rates for the body's particles; mirror particles only lend their (mirrored) state.
  const int n = s.real_count(), all = P.size(), dim = P.dim;
  const bool corrected = S.gradient_correction;
  if (corrected) {
    correction_matrices(s, r.correction);
    mirror_matrices(s, r.correction);
  }
  const bool art = S.artificial_stress > 0.0;
  if (art) {
    artificial_stresses(s, r.art_stress);
    mirror_voigt(s, r.art_stress);
  }
  if (art || S.penalty.pressure > 0.0) {
    // Initial particle spacings (m / rho_ref)^(1/dim), once per call rather than per pair.
    r.spacing.resize(all);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < all; ++i) r.spacing[i] = std::pow(P.mass[i] / P.rho_ref[i], 1.0 / dim);
  }
  r.dv.assign(3 * static_cast<std::size_t>(all), 0.0);
  r.drho.assign(all, 0.0);
  r.de.assign(all, 0.0);
  const bool solids = any_solid(s);
  if (solids) {
    // Velocity gradient L_i = sum_j (m_j / rho_j)(v_j - v_i) (x) grad_i W_ij, and the Jaumann
    // rate of the deviatoric stress.
    r.grad_v.assign(9 * static_cast<std::size_t>(all), 0.0);
    r.dS.assign(6 * static_cast<std::size_t>(all), 0.0);
#pragma omp parallel for schedule(dynamic, 64)
    for (int i = 0; i < n; ++i) {
      const Material& mat = s.materials[P.material[i]];
      if (!mat.strength.enabled) continue;
      const double G = shear_modulus(mat, P.rho[i]);
      double L[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      for (long k = s.pairs.offset[i]; k < s.pairs.offset[i + 1]; ++k) {
        const int j = s.pairs.partner[k];
        double xij[3], r2;
        const double g = pair_gradient(P, dim, S.kernel, i, j, xij, r2);
        if (g == 0.0) continue;
        double gv[3];
        gradient_vector(corrected ? &r.correction[9 * static_cast<std::size_t>(i)] : nullptr, g,
                        xij, gv);
        const double vol = P.mass[j] / P.rho[j];
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) L[a][b] += vol * (P.v[3 * j + a] - P.v[3 * i + a]) * gv[b];
      }
      double D[3][3], W[3][3], Si[3][3];
      const double* s6 = &P.S[6 * static_cast<std::size_t>(i)];
      const double Sm[3][3] = {{s6[0], s6[5], s6[4]}, {s6[5], s6[1], s6[3]}, {s6[4], s6[3], s6[2]}};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          D[a][b] = 0.5 * (L[a][b] + L[b][a]);
          W[a][b] = 0.5 * (L[a][b] - L[b][a]);
          Si[a][b] = Sm[a][b];
        }
      const double trD = D[0][0] + D[1][1] + D[2][2];
      double dS[3][3];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          double rot = 0.0;
          for (int c = 0; c < 3; ++c) rot += W[a][c] * Si[c][b] - Si[a][c] * W[c][b];
          dS[a][b] = 2.0 * G * (D[a][b] - (a == b ? trD / 3.0 : 0.0)) + rot;
        }
      double* out = &r.dS[6 * static_cast<std::size_t>(i)];
      out[0] = dS[0][0], out[1] = dS[1][1], out[2] = dS[2][2];
      out[3] = dS[1][2], out[4] = dS[0][2], out[5] = dS[0][1];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) r.grad_v[9 * static_cast<std::size_t>(i) + 3 * a + b] = L[a][b];
    }
  }
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i) {
    const double pi_rho2 = P.p[i] / (P.rho[i] * P.rho[i]);
    const double* si = &P.S[6 * static_cast<std::size_t>(i)];
    const double ri2 = 1.0 / (P.rho[i] * P.rho[i]);
    double acc[3] = {0.0, 0.0, 0.0}, drho = 0.0, de = 0.0;
    for (long k = s.pairs.offset[i]; k < s.pairs.offset[i + 1]; ++k) {
      const int j = s.pairs.partner[k];
      double xij[3], r2;
      const double g = pair_gradient(P, dim, S.kernel, i, j, xij, r2);
      if (g == 0.0) continue;
      double vij[3], vx = 0.0;
      for (int d = 0; d < 3; ++d) {
        vij[d] = P.v[3 * i + d] - P.v[3 * j + d];
        vx += vij[d] * xij[d];
      }
      const double hij = 0.5 * (P.h[i] + P.h[j]);
      // Monaghan's viscosity for approaching pairs.
      double visc = 0.0;
      if (vx < 0.0) {
        const double mu = hij * vx / (r2 + S.phi * S.phi * hij * hij);
        const double cij = 0.5 * (P.c[i] + P.c[j]), rhoij = 0.5 * (P.rho[i] + P.rho[j]);
        visc = (-S.alpha * cij * mu + S.beta * mu * mu) / rhoij;
      }
      const double q = pi_rho2 + P.p[j] / (P.rho[j] * P.rho[j]) + visc;
      const double mj = P.mass[j];
      // The pair's gradient: with the correction, (C_i + C_j)/2 grad W, which stays
      // antisymmetric in i and j, so momentum is still conserved exactly.
      double gv[3];
      if (corrected) {
        double A[9];
        const double* ci = &r.correction[9 * static_cast<std::size_t>(i)];
        const double* cj = &r.correction[9 * static_cast<std::size_t>(j)];
        for (int c = 0; c < 9; ++c) A[c] = 0.5 * (ci[c] + cj[c]);
        gradient_vector(A, g, xij, gv);
      } else {
        gradient_vector(nullptr, g, xij, gv);
      }
      const double vg = vij[0] * gv[0] + vij[1] * gv[1] + vij[2] * gv[2];
      for (int d = 0; d < 3; ++d) acc[d] -= mj * q * gv[d];
      drho += mj * vg;
      de += 0.5 * mj * q * vg;
      if (solids) {
        // Deviatoric stress: dv_i += m_j (S_i/rho_i^2 + S_j/rho_j^2) . grad W and
        // de_i -= m_j / 2 (S_i/rho_i^2 + S_j/rho_j^2) : (v_ij (x) grad W).
        const double* sj = &P.S[6 * static_cast<std::size_t>(j)];
        const double rj2 = 1.0 / (P.rho[j] * P.rho[j]);
        double T[6];
        for (int c = 0; c < 6; ++c) T[c] = si[c] * ri2 + sj[c] * rj2;
        if (art) {
          // f^n (R_i + R_j), f = W(r) / W(dp) with dp the pair's mean initial spacing.
          const double dp = 0.5 * (r.spacing[i] + r.spacing[j]);
          const double f = kernels::sph_kernel(S.kernel, dim, std::sqrt(r2), hij) /
                           kernels::sph_kernel(S.kernel, dim, dp, hij);
          const double fn = std::pow(f, S.artificial_stress_exponent);
          const double* Ri = &r.art_stress[6 * static_cast<std::size_t>(i)];
          const double* Rj = &r.art_stress[6 * static_cast<std::size_t>(j)];
          for (int c = 0; c < 6; ++c) T[c] += fn * (Ri[c] + Rj[c]);
        }
        const double* gx = gv;
        const double Tg[3] = {T[0] * gx[0] + T[5] * gx[1] + T[4] * gx[2],
                              T[5] * gx[0] + T[1] * gx[1] + T[3] * gx[2],
                              T[4] * gx[0] + T[3] * gx[1] + T[2] * gx[2]};
        for (int d = 0; d < 3; ++d) acc[d] += mj * Tg[d];
        de -= 0.5 * mj * (vij[0] * Tg[0] + vij[1] * Tg[1] + vij[2] * Tg[2]);
      }
      if (S.penalty.pressure > 0.0 && P.material[i] != P.material[j]) {
        const double a = 0.5 * (r.spacing[i] + r.spacing[j]);
        const double r0 = S.penalty.distance * a, rr = std::sqrt(r2);
        if (rr < r0) {
          const double pe = r0 / rr;
          const double f = S.penalty.pressure * std::pow(a, dim - 1) *
                           (std::pow(pe, S.penalty.n1) - std::pow(pe, S.penalty.n2));
          for (int d = 0; d < 3; ++d) acc[d] += f / P.mass[i] * xij[d] / rr;
        }
      }
    }
    if (!P.fixed[i])
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] = acc[d];
    r.drho[i] = drho;
    r.de[i] = de;
  }
  for (const SurfaceLoad& load : s.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      if (P.fixed[i]) continue;
      const double f = load.pulses[k](s.time) * load.area[k] / P.mass[i];
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] += f * load.direction[d];
    }
  for (const TransmittingBoundary& b : s.transmitting)
    for (std::size_t k = 0; k < b.particles.size(); ++k) {
      const int i = b.particles[k];
      double f[3];
      boundary_force(b, k, &P.v[3 * static_cast<std::size_t>(i)], f);
      for (int d = 0; d < 3; ++d) r.dv[3 * i + d] += f[d] / P.mass[i];
    }
}

namespace {
/// The forces of the surface loads and the boundaries at the current state, particle by
/// particle (a particle may appear more than once).
void external_forces(const Hydro& s, std::vector<int>& who, std::vector<double>& force) {
  const Particles& P = s.particles;
  who.clear();
  force.clear();
  for (const SurfaceLoad& load : s.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      if (P.fixed[i]) continue;
      const double f = load.pulses[k](s.time) * load.area[k];
      who.push_back(i);
      for (int d = 0; d < 3; ++d) force.push_back(f * load.direction[d]);
    }
  for (const TransmittingBoundary& b : s.transmitting)
    for (std::size_t k = 0; k < b.particles.size(); ++k) {
      double f[3];
      boundary_force(b, k, &P.v[3 * static_cast<std::size_t>(b.particles[k])], f);
      who.push_back(b.particles[k]);
      for (int d = 0; d < 3; ++d) force.push_back(f[d]);
    }
}
} // namespace

double stable_step(const Hydro& s, int* limiting) {
  const Particles& P = s.particles;
  double best = std::numeric_limits<double>::infinity();
  int where = -1;
  for (int i = 0; i < s.real_count(); ++i) {
    const double speed = std::sqrt(P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] +
                                   P.v[3 * i + 2] * P.v[3 * i + 2]);
    const double dt = P.h[i] / (P.c[i] + speed);
    if (dt < best) best = dt, where = i;
  }
  if (limiting) *limiting = where;
  return s.settings.courant * best;
}

namespace {
void check_finite(const Hydro& s) {
  const Particles& P = s.particles;
  for (int i = 0; i < P.size(); ++i)
    if (!std::isfinite(P.rho[i]) || !std::isfinite(P.e[i]) || !(P.rho[i] > 0.0) ||
        !std::isfinite(P.v[3 * i]) || !std::isfinite(P.v[3 * i + 1]) ||
        !std::isfinite(P.v[3 * i + 2]))
      fail("SPH: particle ", i, " at (", P.x[3 * i], ", ", P.x[3 * i + 1], ", ", P.x[3 * i + 2],
           ") has density ", P.rho[i], ", energy ", P.e[i], ", velocity (", P.v[3 * i], ", ",
           P.v[3 * i + 1], ", ", P.v[3 * i + 2], ") at step ", s.step, ", t = ", s.time);
}
} // namespace

namespace {
/// S = S0 + dt dS, returned radially to the yield surface of the particle's model at its current
/// pressure; the plastic strain and the damage grow from their values at the start of the step.
void update_stress(Hydro& s, const std::vector<double>& S0, const std::vector<double>& alpha0,
                   const std::vector<double>& damage0, const Rates& r, double dt) {
  Particles& P = s.particles;
  const int n = s.real_count();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const Material& mat = s.materials[P.material[i]];
    const Strength& st = mat.strength;
    if (!st.enabled) continue;
    double* si = &P.S[6 * static_cast<std::size_t>(i)];
    if (P.failed[i]) {
      for (int c = 0; c < 6; ++c) si[c] = 0.0;
      continue;
    }
    for (int c = 0; c < 6; ++c) si[c] = S0[6 * i + c] + dt * r.dS[6 * i + c];
    P.alpha[i] = alpha0[i];
    P.damage[i] = damage0[i];
    // Equivalent deviatoric strain rate sqrt(2/3 D':D') from the velocity gradient.
    const double* L = &r.grad_v[9 * static_cast<std::size_t>(i)];
    const double tr = (L[0] + L[4] + L[8]) / 3.0;
    double dd = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double d = 0.5 * (L[3 * a + b] + L[3 * b + a]) - (a == b ? tr : 0.0);
        dd += d * d;
      }
    P.strain_rate[i] = std::sqrt(2.0 / 3.0 * dd);
    if (!st.plastic()) continue;
    const double q = std::sqrt(1.5 * (si[0] * si[0] + si[1] * si[1] + si[2] * si[2] +
                                      2.0 * (si[3] * si[3] + si[4] * si[4] + si[5] * si[5])));
    if (st.model == Strength::Model::VonMises) {
      const materials::DeviatoricReturn ret =
          materials::j2_return_deviatoric(st.yield, q, alpha0[i]);
      for (int c = 0; c < 6; ++c) si[c] *= ret.scale;
      P.alpha[i] = alpha0[i] + ret.dalpha;
    } else {
      // Perfectly plastic at the current pressure (and damage): radial return to Y, with the
      // plastic strain increment (q - Y) / 3G.
      const double Y = current_yield(mat, P.p[i], alpha0[i], damage0[i], P.strain_rate[i]);
      double dalpha = 0.0;
      if (q > Y) {
        const double scale = q > 0.0 ? Y / q : 0.0;
        for (int c = 0; c < 6; ++c) si[c] *= scale;
        dalpha = (q - Y) / (3.0 * shear_modulus(mat, P.rho[i]));
      }
      P.alpha[i] = alpha0[i] + dalpha;
      if (st.model == Strength::Model::Hjc) {
        // HJC damage: plastic strain plus plastic volumetric compaction (the growth of the
        // largest compression beyond the crush point) over the strain to fracture.
        const materials::Hjc& m = mat.hjc;
        const double mu = P.rho[i] / m.rho0 - 1.0, mu_max = P.rho_max[i] / m.rho0 - 1.0;
        const double dmu = mu > mu_max && mu > m.mu_crush ? mu - std::max(mu_max, m.mu_crush) : 0.0;
        P.damage[i] =
            std::min(1.0, damage0[i] + (dalpha + dmu) / materials::hjc_fracture_strain(m, P.p[i]));
      }
    }
  }
}

/// Marks the particles whose damage or plastic strain has reached failure, and commits the
/// largest density reached.
void commit_history(Hydro& s) {
  Particles& P = s.particles;
  const int n = P.size();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.rho_max[i] = std::max(P.rho_max[i], P.rho[i]);
    const Strength& st = s.materials[P.material[i]].strength;
    if (!st.enabled || P.failed[i]) continue;
    if ((st.model == Strength::Model::Hjc && P.damage[i] >= 1.0) ||
        (st.failure_strain > 0.0 && P.alpha[i] >= st.failure_strain)) {
      P.failed[i] = 1;
      for (int c = 0; c < 6; ++c) P.S[6 * static_cast<std::size_t>(i) + c] = 0.0;
    }
  }
}
} // namespace

void advance(Hydro& s, double dt) {
  Particles& P = s.particles;
  const int n = s.real_count(); // mirror particles are copied from these after each stage
  const std::size_t n3 = 3 * static_cast<std::size_t>(n);
  const std::vector<double> x0 = P.x, v0 = P.v, rho0 = P.rho, e0 = P.e, S0 = P.S, a0 = P.alpha,
                            D0 = P.damage;
  const bool solids = any_solid(s);
  const double t0 = s.time;
  Rates r;
  // Predictor: half a step with the rates at the start.
  refresh_neighbours(s);
  compute_rates(s, r);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.x[k] = x0[k] + 0.5 * dt * v0[k];
    P.v[k] = v0[k] + 0.5 * dt * r.dv[k];
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.rho[i] = rho0[i] + 0.5 * dt * r.drho[i];
    P.e[i] = e0[i] + 0.5 * dt * r.de[i];
  }
  if (solids) update_stress(s, S0, a0, D0, r, 0.5 * dt);
  s.time = t0 + 0.5 * dt;
  refresh_ghosts(s);
  update_state(s);
  // The loads' forces at the midpoint, which the corrector applies over the whole step.
  std::vector<int> loaded;
  std::vector<double> mid_force;
  external_forces(s, loaded, mid_force);
  // Corrector: the full step with the mid-step rates.
  refresh_neighbours(s);
  compute_rates(s, r);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n3; ++k) {
    P.x[k] = x0[k] + dt * P.v[k];
    P.v[k] = v0[k] + dt * r.dv[k];
  }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    P.rho[i] = rho0[i] + dt * r.drho[i];
    P.e[i] = e0[i] + dt * r.de[i];
  }
  if (solids) update_stress(s, S0, a0, D0, r, dt);
  // Their work: F_mid . (v0 + v1) / 2 dt, which is exactly the kinetic energy the corrector's
  // velocity update gives them, pulses that arrive within the step included.
  for (std::size_t k = 0; k < loaded.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const std::size_t at = 3 * static_cast<std::size_t>(loaded[k]) + d;
      s.external_work += dt * mid_force[3 * k + d] * 0.5 * (v0[at] + P.v[at]);
    }
  s.time = t0 + dt;
  ++s.step;
  check_finite(s);
  commit_history(s);
  refresh_ghosts(s);
  update_state(s);
}

Energies energies(const Hydro& s) {
  const Particles& P = s.particles;
  Energies out;
  for (int i = 0; i < s.real_count(); ++i) {
    const double v2 =
        P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] + P.v[3 * i + 2] * P.v[3 * i + 2];
    out.kinetic += 0.5 * P.mass[i] * v2;
    out.internal += P.mass[i] * P.e[i];
  }
  return out;
}

} // namespace mf::sph
