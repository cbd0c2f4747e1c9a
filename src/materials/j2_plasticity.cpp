#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>

namespace mf::materials {

namespace {

const double kSqrt23 = std::sqrt(2.0 / 3.0);

/// m = [1 1 1 0 0 0]
Vec6 unit_trace() {
  Vec6 m = Vec6::Zero();
  m.head<3>().setOnes();
  return m;
}

/// Deviatoric part of a stress-like Voigt vector.
Vec6 deviator(const Vec6& s) {
  Vec6 d = s;
  d.head<3>().array() -= s.head<3>().sum() / 3.0;
  return d;
}

/// Tensor norm of a stress-like Voigt vector: sqrt(s : s).
double tensor_norm(const Vec6& s) {
  return std::sqrt(s.head<3>().squaredNorm() + 2.0 * s.tail<3>().squaredNorm());
}

/// Stress-like to strain-like (engineering shear) Voigt.
Vec6 engineering(const Vec6& t) {
  Vec6 e = t;
  e.tail<3>() *= 2.0;
  return e;
}

struct Yield {
  double operator()(const PerfectPlastic&) const { return s0; }
  double operator()(const LinearHardening& h) const { return s0 + h.H * a; }
  double operator()(const VoceHardening& h) const {
    return s0 + h.H * a + (h.sigma_inf - s0) * (1.0 - std::exp(-h.delta * a));
  }
  double operator()(const SwiftHardening& h) const { return h.K * std::pow(h.eps0 + a, h.n); }
  double operator()(const TableHardening& h) const {
    const std::size_t n = h.alpha.size();
    std::size_t k = std::upper_bound(h.alpha.begin(), h.alpha.end(), a) - h.alpha.begin();
    k = std::clamp<std::size_t>(k, 1, n - 1);
    const double slope = (h.sigma[k] - h.sigma[k - 1]) / (h.alpha[k] - h.alpha[k - 1]);
    return h.sigma[k - 1] + slope * (a - h.alpha[k - 1]);
  }
  double s0, a;
};

struct Slope {
  double operator()(const PerfectPlastic&) const { return 0.0; }
  double operator()(const LinearHardening& h) const { return h.H; }
  double operator()(const VoceHardening& h) const {
    return h.H + (h.sigma_inf - s0) * h.delta * std::exp(-h.delta * a);
  }
  double operator()(const SwiftHardening& h) const {
    return h.n * h.K * std::pow(h.eps0 + a, h.n - 1.0);
  }
  double operator()(const TableHardening& h) const {
    const std::size_t n = h.alpha.size();
    std::size_t k = std::upper_bound(h.alpha.begin(), h.alpha.end(), a) - h.alpha.begin();
    k = std::clamp<std::size_t>(k, 1, n - 1);
    return (h.sigma[k] - h.sigma[k - 1]) / (h.alpha[k] - h.alpha[k - 1]);
  }
  double s0, a;
};

} // namespace

double yield_stress(const J2Parameters& p, double alpha) {
  return std::visit(Yield{p.sigma0, alpha}, p.hardening);
}

double yield_slope(const J2Parameters& p, double alpha) {
  return std::visit(Slope{p.sigma0, alpha}, p.hardening);
}

double von_mises_3d(const Vec6& s) {
  return std::sqrt(1.5) * tensor_norm(deviator(s));
}

J2Return j2_radial_return(const J2Parameters& p, const Vec6& s_trial, const Vec6& back_stress,
                          double alpha) {
  const double mu = p.E / (2.0 * (1.0 + p.nu));
  J2Return r;
  r.alpha = alpha;
  r.deviator = s_trial;
  r.back_stress = back_stress;
  const Vec6 xi_trial = s_trial - back_stress;
  const double xi_norm = tensor_norm(xi_trial);
  r.trial_norm = xi_norm;
  const double f_trial = xi_norm - kSqrt23 * yield_stress(p, alpha);
  if (f_trial <= 0.0 || xi_norm == 0.0) return r;

  // Consistency: g(dgamma) = |xi_trial| - 2 mu dgamma - (2/3) Hk dgamma
  //                         - sqrt(2/3) sigma_y(alpha_n + sqrt(2/3) dgamma) = 0   (Box 3.2).
  double dgamma = 0.0;
  for (int it = 0;; ++it) {
    const double a = alpha + kSqrt23 * dgamma;
    const double g = xi_norm - 2.0 * mu * dgamma - 2.0 / 3.0 * p.H_kinematic * dgamma -
                     kSqrt23 * yield_stress(p, a);
    const double dg = -2.0 * mu * (1.0 + (yield_slope(p, a) + p.H_kinematic) / (3.0 * mu));
    const double step = -g / dg;
    dgamma += step;
    if (std::abs(step) <= 1e-15 * std::max(dgamma, 1e-300) || std::abs(g) <= 1e-13 * xi_norm) break;
    if (it == 50)
      fail("J2 return mapping did not converge in 50 iterations (residual ", g, ", trial norm ",
           xi_norm, ")");
  }
  r.plastic = true;
  r.dgamma = dgamma;
  r.alpha = alpha + kSqrt23 * dgamma;
  r.normal = xi_trial / xi_norm; // stress-like unit normal
  r.deviator = s_trial - 2.0 * mu * dgamma * r.normal;
  r.back_stress = back_stress + 2.0 / 3.0 * p.H_kinematic * dgamma * r.normal;
  return r;
}

J2Result3D j2_update_3d(const J2Parameters& p, const Vec6& strain, const J2State& committed) {
  const double mu = p.E / (2.0 * (1.0 + p.nu));
  const double kappa = p.E / (3.0 * (1.0 - 2.0 * p.nu));
  const Vec6 m = unit_trace();
  Mat6 I_sym = Mat6::Identity();
  I_sym.diagonal().tail<3>().setConstant(0.5); // maps engineering strain to tensor strain
  const Mat6 I_dev = I_sym - m * m.transpose() / 3.0;

  // Elastic trial state (Simo & Hughes Box 3.1, step 1), returned radially (Box 3.2).
  const Vec6 eps_e = strain - committed.plastic_strain;
  const double volumetric = eps_e.head<3>().sum();
  const Vec6 s_trial = 2.0 * mu * (I_dev * eps_e); // deviatoric stress, stress-like
  const J2Return ret = j2_radial_return(p, s_trial, committed.back_stress, committed.alpha);

  J2Result3D r;
  r.state = committed;
  if (!ret.plastic) {
    r.stress = kappa * volumetric * m + s_trial;
    r.tangent = kappa * m * m.transpose() + 2.0 * mu * I_dev;
    return r;
  }
  const double dgamma = ret.dgamma, alpha = ret.alpha;
  const Vec6& n = ret.normal;
  r.plastic = true;
  r.state.alpha = alpha;
  r.state.back_stress = ret.back_stress;
  r.state.plastic_strain = committed.plastic_strain + dgamma * engineering(n);
  r.stress = kappa * volumetric * m + s_trial - 2.0 * mu * dgamma * n;

  // Consistent tangent (Box 3.2): C = kappa 1x1 + 2 mu theta I_dev - 2 mu theta_bar n x n.
  const double theta = 1.0 - 2.0 * mu * dgamma / ret.trial_norm;
  const double theta_bar =
      1.0 / (1.0 + (yield_slope(p, alpha) + p.H_kinematic) / (3.0 * mu)) - (1.0 - theta);
  r.tangent = kappa * m * m.transpose() + 2.0 * mu * theta * I_dev -
              2.0 * mu * theta_bar * n * n.transpose();
  return r;
}

namespace {

/// Embeds [xx, yy, xy] and eps_zz into a 3D strain.
Vec6 embed(const Vec3& e, double ezz) {
  Vec6 s = Vec6::Zero();
  s << e(0), e(1), ezz, 0.0, 0.0, e(2);
  return s;
}

J2Result2D reduce(const J2Result3D& r3, double ezz) {
  J2Result2D r;
  for (int a = 0; a < 3; ++a) {
    r.stress(a) = r3.stress(kPlane[a]);
    for (int b = 0; b < 3; ++b) r.tangent(a, b) = r3.tangent(kPlane[a], kPlane[b]);
  }
  r.stress_zz = r3.stress(2);
  r.strain_zz = ezz;
  r.state = r3.state;
  r.plastic = r3.plastic;
  return r;
}

} // namespace

J2Result2D j2_update_plane_strain(const J2Parameters& p, const Vec3& strain,
                                  const J2State& committed) {
  return reduce(j2_update_3d(p, embed(strain, 0.0), committed), 0.0);
}

J2Result2D j2_update_plane_stress(const J2Parameters& p, const Vec3& strain,
                                  const J2State& committed) {
  // Start from the elastic plane-stress guess for eps_zz (plastic flow is isochoric).
  const Vec6& ep = committed.plastic_strain;
  double ezz = ep(2) - p.nu / (1.0 - p.nu) * ((strain(0) - ep(0)) + (strain(1) - ep(1)));
  J2Result3D r3;
  const double scale = std::max(p.sigma0, yield_stress(p, committed.alpha));
  // Newton on eps_zz: quadratic until sigma_zz reaches the round-off of the 3D return (about
  // 1e-15 of the stress, times the conditioning of the plastic tangent); it stops there, or when
  // the correction no longer changes eps_zz.
  const double strain_size = std::max(strain.cwiseAbs().maxCoeff(), std::abs(ezz));
  for (int it = 0;; ++it) {
    r3 = j2_update_3d(p, embed(strain, ezz), committed);
    if (std::abs(r3.stress(2)) <= 1e-12 * scale) break;
    const double step = r3.stress(2) / r3.tangent(2, 2);
    if (std::abs(step) <= 1e-15 * strain_size && std::abs(r3.stress(2)) <= 1e-8 * scale) break;
    if (it == 50)
      fail("plane-stress return did not converge in 50 iterations (sigma_zz = ", r3.stress(2), ")");
    ezz -= step;
  }
  J2Result2D r = reduce(r3, ezz);
  // Static condensation of sigma_zz = 0: d eps_zz = -C_zp d eps_p / C_zz.
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      r.tangent(a, b) -= r3.tangent(kPlane[a], 2) * r3.tangent(2, kPlane[b]) / r3.tangent(2, 2);
  return r;
}

} // namespace mf::materials
