#include "meshfree/materials/j2_plasticity.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/materials/elastic.hpp"
#include <algorithm>
#include <cmath>
#include <utility>

namespace mf::materials {

using voigt::deviator;
using voigt::engineering;
using voigt::tensor_norm;
using voigt::unit_trace;

namespace {

const double kSqrt23 = std::sqrt(2.0 / 3.0);
const double kSqrt23Cubed = kSqrt23 * kSqrt23 * kSqrt23; // (2/3)^(3/2)

/// The uniaxial yield stress sigma_y(alpha) and its slope, together (Voce: one exponential).
struct YieldCurve {
  using Point = std::pair<double, double>;
  Point operator()(const PerfectPlastic&) const { return {s0, 0.0}; }
  Point operator()(const LinearHardening& h) const { return {s0 + h.H * a, h.H}; }
  Point operator()(const VoceHardening& h) const {
    const double decay = std::exp(-h.delta * a);
    return {s0 + h.H * a + (h.sigma_inf - s0) * (1.0 - decay),
            h.H + (h.sigma_inf - s0) * h.delta * decay};
  }
  Point operator()(const SwiftHardening& h) const {
    return {h.K * std::pow(h.eps0 + a, h.n), h.n * h.K * std::pow(h.eps0 + a, h.n - 1.0)};
  }
  Point operator()(const TableHardening& h) const {
    const std::size_t n = h.alpha.size();
    std::size_t k = std::upper_bound(h.alpha.begin(), h.alpha.end(), a) - h.alpha.begin();
    k = std::clamp<std::size_t>(k, 1, n - 1);
    const double slope = (h.sigma[k] - h.sigma[k - 1]) / (h.alpha[k] - h.alpha[k - 1]);
    return {h.sigma[k - 1] + slope * (a - h.alpha[k - 1]), slope};
  }
  double s0, a;
};

std::pair<double, double> yield_curve(const J2Parameters& p, double alpha) {
  return std::visit(YieldCurve{p.sigma0, alpha}, p.hardening);
}

} // namespace

double yield_stress(const J2Parameters& p, double alpha) {
  return yield_curve(p, alpha).first;
}

double yield_slope(const J2Parameters& p, double alpha) {
  return yield_curve(p, alpha).second;
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
    const auto [sy, slope] = yield_curve(p, a);
    const double g =
        xi_norm - 2.0 * mu * dgamma - 2.0 / 3.0 * p.H_kinematic * dgamma - kSqrt23 * sy;
    const double dg = -2.0 * mu * (1.0 + (slope + p.H_kinematic) / (3.0 * mu));
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

StressUpdate3D j2_update_3d(const J2Parameters& p, const Vec6& strain,
                            const MaterialState& committed) {
  const double mu = p.E / (2.0 * (1.0 + p.nu));
  const double kappa = p.E / (3.0 * (1.0 - 2.0 * p.nu));
  const Vec6 m = unit_trace();
  const Mat6 I_dev = voigt::deviatoric_projector();

  // Elastic trial state (Simo & Hughes Box 3.1, step 1), returned radially (Box 3.2).
  const Vec6 eps_e = strain - committed.plastic_strain;
  const double volumetric = eps_e.head<3>().sum();
  const Vec6 s_trial = 2.0 * mu * (I_dev * eps_e); // deviatoric stress, stress-like
  const J2Return ret = j2_radial_return(p, s_trial, committed.back_stress, committed.alpha);

  StressUpdate3D r;
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

StressUpdate2D j2_update_plane_strain(const J2Parameters& p, const Vec3& strain,
                                      const MaterialState& committed) {
  return voigt::reduce(j2_update_3d(p, voigt::embed(strain, 0.0), committed), 0.0);
}

namespace {

/// The plane-stress return in the eigenbasis shared by the projection P (s : s = sigma^T P sigma,
/// P = [2 -1 0; -1 2 0; 0 0 6] / 3) and the plane-stress elasticity C: the vectors (1, 1, 0) / sqrt
/// 2, (1, -1, 0) / sqrt 2 and (0, 0, 1), with eigenvalues p = (1/3, 1, 2) of P and c = (E / (1 -
/// nu), 2 mu, mu) of C (engineering shear).
struct PlaneStressBasis {
  Vec3 p, c;
  explicit PlaneStressBasis(const J2Parameters& m) {
    const double mu = m.E / (2.0 * (1.0 + m.nu));
    p = Vec3(1.0 / 3.0, 1.0, 2.0);
    c = Vec3(m.E / (1.0 - m.nu), 2.0 * mu, mu);
  }
  static Vec3 to(const Vec3& v) { // components on the eigenvectors
    return Vec3((v(0) + v(1)) / std::sqrt(2.0), (v(0) - v(1)) / std::sqrt(2.0), v(2));
  }
  static Mat3 from_diagonal(const Vec3& d) { // Q diag(d) Q^T
    Mat3 m = Mat3::Zero();
    m(0, 0) = m(1, 1) = 0.5 * (d(0) + d(1));
    m(0, 1) = m(1, 0) = 0.5 * (d(0) - d(1));
    m(2, 2) = d(2);
    return m;
  }
};

const Mat3& projection() {
  static const Mat3 P = (Mat3() << 2.0, -1.0, 0.0, -1.0, 2.0, 0.0, 0.0, 0.0, 6.0).finished() / 3.0;
  return P;
}

/// xi2(lambda) = |dev eta|^2 = sum_i p_i eta_trial,i^2 / d_i^2 with d_i = 1 + lambda (c_i p_i +
/// (2/3) Hk), in the eigenbasis, and its derivative.
struct ProjectedTrial {
  Vec3 w2;   // p_i eta_trial,i^2
  Vec3 rate; // c_i p_i + (2/3) Hk
  Vec3 d(double lambda) const { return (1.0 + lambda * rate.array()).matrix(); }
  double xi2(double lambda) const { return (w2.array() / d(lambda).array().square()).sum(); }
  double dxi2(double lambda) const {
    return (-2.0 * w2.array() * rate.array() / d(lambda).array().cube()).sum();
  }
};

/// The lambda of the consistency condition xi = sqrt(2/3) sigma_y(alpha_n + sqrt(2/3) lambda xi),
/// xi = |dev eta|, by Newton on H(lambda) = 1 / xi - 1 / (sqrt(2/3) sigma_y) from the elastic end
/// (H(0) < 0). 1 / xi is linear in lambda where one mode carries the trial stress (one step for a
/// perfectly plastic law), so far roots are reached in a few steps, where Newton on xi^2 / 2 -
/// sigma_y^2 / 3 from lambda = 0 lengthens its steps by only half each time.
double plastic_multiplier(const J2Parameters& p, const ProjectedTrial& t, double alpha_n) {
  double lambda = 0.0;
  for (int it = 0;; ++it) {
    const double xi2 = t.xi2(lambda), xi = std::sqrt(xi2), dxi = t.dxi2(lambda) / (2.0 * xi);
    const auto [sy, slope] = yield_curve(p, alpha_n + kSqrt23 * lambda * xi);
    const double H = 1.0 / xi - 1.0 / (kSqrt23 * sy);
    const double dalpha = kSqrt23 * (xi + lambda * dxi);
    const double step = -H / (-dxi / xi2 + slope * dalpha / (kSqrt23 * sy * sy));
    lambda = std::max(lambda + step, 0.0);
    if (std::abs(step) <= 1e-15 * std::max(lambda, 1e-300) || std::abs(H) * xi <= 1e-15)
      return lambda;
    if (it == 50)
      fail("plane-stress return did not converge in 50 iterations (1 - xi / (sqrt(2/3) "
           "sigma_y) = ",
           H * xi, ", trial |dev eta|^2 ", t.xi2(0.0), ")");
  }
}

/// The consistent tangent of the projected return: Xi = [C^-1 + (lambda / k) P]^-1 and
/// D = Xi - (Xi P eta)(Xi P eta)^T / (k^2 B / A + (2/3) Hk k xi2 + eta^T P Xi P eta), with
/// k = 1 + (2/3) Hk lambda, A = 1 - (2/3)^(3/2) sigma_y sigma_y' lambda / xi and
/// B = (2/3)^(3/2) sigma_y sigma_y' xi (the linearised consistency condition; Hk = 0 gives the
/// book's beta_bar = B / A).
Mat3 projected_tangent(const J2Parameters& p, const PlaneStressBasis& e, const Vec3& eta,
                       double lambda, double alpha) {
  const Mat3& P = projection();
  const double k = 1.0 + 2.0 / 3.0 * p.H_kinematic * lambda;
  const double xi2 = eta.dot(P * eta), xi = std::sqrt(xi2);
  const Vec3 xi_diag = (e.c.array() / (1.0 + lambda / k * e.c.array() * e.p.array())).matrix();
  const Mat3 Xi = PlaneStressBasis::from_diagonal(xi_diag);
  const Vec3 n = Xi * (P * eta);
  const auto [sy, slope] = yield_curve(p, alpha);
  const double hs = kSqrt23Cubed * sy * slope;
  const double A = 1.0 - hs * lambda / xi, B = hs * xi;
  const double denominator = k * k * B / A + 2.0 / 3.0 * p.H_kinematic * k * xi2 + eta.dot(P * n);
  return Xi - n * n.transpose() / denominator;
}

} // namespace

StressUpdate2D j2_update_plane_stress(const J2Parameters& p, const Vec3& strain,
                                      const MaterialState& committed) {
  // The plane-stress projected return ([Simo & Taylor 1986]; [de Souza Neto, Peric & Owen 2008]
  // ch. 9), with linear kinematic hardening: eta = sigma - b is the stress relative to the plane
  // stress b whose deviator is the back stress beta, and with lambda = dgamma / |dev eta| the
  // backward-Euler step is
  //   sigma = C (eps - eps_p,n - lambda P eta),   b = b_n + (2/3) Hk lambda eta,
  //   eta_i = eta_trial,i / (1 + lambda (c_i p_i + (2/3) Hk))   (in the eigenbasis),
  // lambda from the consistency condition (plastic_multiplier); the same solution as the 3D return
  // with sigma_zz = 0.
  const PlaneStressBasis e(p);
  const Mat3& P = projection();
  const Vec6& ep = committed.plastic_strain;
  const Vec6& beta = committed.back_stress;
  const Vec3 elastic_strain(strain(0) - ep(0), strain(1) - ep(1), strain(2) - ep(5));
  const Mat3 C = elastic_matrix({p.E, p.nu}, PlaneModel::PlaneStress);
  const Vec3 sigma_trial = C * elastic_strain;
  const Vec3 b_n(beta(0) - beta(2), beta(1) - beta(2), beta(5));
  const Vec3 eta_trial = sigma_trial - b_n;
  const double xi2_trial = eta_trial.dot(P * eta_trial);
  if (!std::isfinite(xi2_trial))
    fail("plane-stress return: the trial stress is not finite (strain ", strain.transpose(), ")");

  StressUpdate2D r;
  r.state = committed;
  r.stress = sigma_trial;
  r.tangent = C;
  r.strain_zz = ep(2) - p.nu / p.E * (sigma_trial(0) + sigma_trial(1));
  if (std::sqrt(xi2_trial) - kSqrt23 * yield_stress(p, committed.alpha) <= 0.0 || xi2_trial == 0.0)
    return r;

  const Vec3 t = PlaneStressBasis::to(eta_trial);
  const ProjectedTrial trial{e.p.cwiseProduct(t.cwiseProduct(t)),
                             (e.c.cwiseProduct(e.p).array() + 2.0 / 3.0 * p.H_kinematic).matrix()};
  const double lambda = plastic_multiplier(p, trial, committed.alpha);
  const double alpha = committed.alpha + kSqrt23 * lambda * std::sqrt(trial.xi2(lambda));
  const Vec3 eta =
      PlaneStressBasis::from_diagonal((1.0 / trial.d(lambda).array()).matrix()) * eta_trial;
  const Vec3 dep = lambda * (P * eta); // plastic strain increment, engineering shear
  const double dep_zz = -lambda * (eta(0) + eta(1)) / 3.0;
  r.plastic = true;
  r.stress = sigma_trial - C * dep;
  r.strain_zz = ep(2) + dep_zz - p.nu / p.E * (r.stress(0) + r.stress(1));
  r.tangent = projected_tangent(p, e, eta, lambda, alpha);
  r.state.alpha = alpha;
  r.state.plastic_strain(0) += dep(0);
  r.state.plastic_strain(1) += dep(1);
  r.state.plastic_strain(2) += dep_zz;
  r.state.plastic_strain(5) += dep(2);
  // beta += (2/3) Hk lambda dev(eta), dev(eta) of the plane stress eta (eta_zz = 0).
  const double kin = 2.0 / 3.0 * p.H_kinematic * lambda;
  r.state.back_stress(0) += kin * (2.0 * eta(0) - eta(1)) / 3.0;
  r.state.back_stress(1) += kin * (2.0 * eta(1) - eta(0)) / 3.0;
  r.state.back_stress(2) -= kin * (eta(0) + eta(1)) / 3.0;
  r.state.back_stress(5) += kin * eta(2);
  return r;
}

} // namespace mf::materials
