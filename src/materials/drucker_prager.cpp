#include "meshfree/materials/drucker_prager.hpp"
#include "meshfree/core/error.hpp"
#include <cmath>

namespace mf::materials {

namespace {

const double kSqrt2 = std::sqrt(2.0);

/// The elastic trial state and what every return uses of it.
struct Trial {
  double G = 0.0, K = 0.0;
  Vec6 s = Vec6::Zero(); // trial deviator, stress-like
  double p = 0.0;        // trial mean stress
  double J = 0.0;        // sqrt(J2(s)) = |s| / sqrt 2
  Vec6 n = Vec6::Zero(); // s / |s| (zero at |s| = 0)
  double c = 0.0;        // committed cohesion
};

Trial trial_state(const DruckerPragerParameters& p, const Vec6& strain,
                  const MaterialState& committed) {
  Trial t;
  t.G = p.E / (2.0 * (1.0 + p.nu));
  t.K = p.E / (3.0 * (1.0 - 2.0 * p.nu));
  const Vec6 eps_e = strain - committed.plastic_strain;
  t.s = 2.0 * t.G * (voigt::deviatoric_projector() * eps_e);
  t.p = t.K * eps_e.head<3>().sum();
  const double norm = voigt::tensor_norm(t.s);
  t.J = norm / kSqrt2;
  if (norm > 0.0) t.n = t.s / norm;
  t.c = p.cohesion + p.hardening * committed.alpha;
  if (!std::isfinite(t.p) || !std::isfinite(t.J))
    fail("Drucker-Prager update: the trial stress is not finite (strain ", strain.transpose(), ")");
  return t;
}

/// sigma = s + p m and the history with plastic strain increment dep and alpha increment.
StressUpdate3D plastic_result(const Vec6& s, double p, const MaterialState& committed,
                              const Vec6& dep, double dalpha) {
  StressUpdate3D r;
  r.stress = s + p * voigt::unit_trace();
  r.state = committed;
  r.state.plastic_strain += dep;
  r.state.alpha += dalpha;
  r.plastic = true;
  return r;
}

/// The smooth cone: dgamma = Phi_trial / (G + K eta eta_bar + xi^2 H) (linear hardening), and
/// the tangent
///   D = 2G (1 - sqrt2 G dgamma / |s_tr|)(I_dev - n n) + 2G (1 - G A) n n
///       - sqrt2 G A K (eta n m + eta_bar m n) + K (1 - K eta eta_bar A) m m,
/// A = 1 / (G + K eta eta_bar + xi^2 H) (de Souza Neto et al. 2008, section 8.3, in this notation;
/// derived again here).
StressUpdate3D cone_return(const DruckerPragerParameters& p, const Trial& t, double dgamma,
                           const MaterialState& committed) {
  const double G = t.G, K = t.K;
  const double A = 1.0 / (G + K * p.eta * p.eta_bar + p.xi * p.xi * p.hardening);
  const double J = t.J - G * dgamma;
  const Vec6 m = voigt::unit_trace();
  const Vec6 dep = dgamma * (voigt::engineering(t.n) / kSqrt2 + p.eta_bar / 3.0 * m);
  StressUpdate3D r =
      plastic_result(kSqrt2 * J * t.n, t.p - K * p.eta_bar * dgamma, committed, dep, p.xi * dgamma);
  const Mat6 nn = t.n * t.n.transpose();
  r.tangent = 2.0 * G * (J / t.J) * (voigt::deviatoric_projector() - nn) +
              2.0 * G * (1.0 - G * A) * nn -
              kSqrt2 * G * A * K * (p.eta * t.n * m.transpose() + p.eta_bar * m * t.n.transpose()) +
              K * (1.0 - K * p.eta * p.eta_bar * A) * m * m.transpose();
  return r;
}

/// The apex: s = 0 and p = xi c(alpha) / eta, with alpha' = (xi / eta_bar) eps_v^p (de Souza
/// Neto et al. 2008, section 8.3); without dilatancy (eta_bar = 0) the apex does not harden.
/// D = K (1 - K / (K + a b H)) m m, a = xi / eta_bar, b = xi / eta.
StressUpdate3D apex_return(const DruckerPragerParameters& p, const Trial& t,
                           const MaterialState& committed) {
  const double a = p.eta_bar > 0.0 ? p.xi / p.eta_bar : 0.0, b = p.xi / p.eta;
  const double stiffness = t.K + a * b * p.hardening;
  const double dev_p = (t.p - b * t.c) / stiffness; // volumetric plastic strain
  const Vec6 m = voigt::unit_trace();
  const Vec6 dep = voigt::engineering(t.s) / (2.0 * t.G) + dev_p / 3.0 * m;
  StressUpdate3D r = plastic_result(Vec6::Zero(), t.p - t.K * dev_p, committed, dep, a * dev_p);
  r.tangent = t.K * (1.0 - t.K / stiffness) * m * m.transpose();
  return r;
}

/// The tension cut-off p = T: alone (the deviator stays), or with the cone on their circle of
/// intersection, where dgamma = (J_tr + eta T - xi c) / (G + xi^2 H) shrinks the deviator and
///   D = 2G (J / J_tr)(I_dev - n n) + 2G xi^2 H / (G + xi^2 H) n n   (dp = 0).
StressUpdate3D cutoff_return(const DruckerPragerParameters& p, const Trial& t,
                             const MaterialState& committed) {
  const double T = p.tension_cutoff;
  const Vec6 m = voigt::unit_trace();
  const double dev_p = (t.p - T) / t.K; // volumetric plastic strain, both cases
  const double phi = t.J + p.eta * T - p.xi * t.c;
  const Mat6 I_dev = voigt::deviatoric_projector();
  if (phi <= 0.0) {
    StressUpdate3D r = plastic_result(t.s, T, committed, dev_p / 3.0 * m, 0.0);
    r.tangent = 2.0 * t.G * I_dev;
    return r;
  }
  const double hx = p.xi * p.xi * p.hardening;
  const double dgamma = phi / (t.G + hx);
  const double J = t.J - t.G * dgamma;
  const Vec6 dep = dgamma * voigt::engineering(t.n) / kSqrt2 + dev_p / 3.0 * m;
  StressUpdate3D r = plastic_result(kSqrt2 * J * t.n, T, committed, dep, p.xi * dgamma);
  const Mat6 nn = t.n * t.n.transpose();
  r.tangent = 2.0 * t.G * (J / t.J) * (I_dev - nn) + 2.0 * t.G * hx / (t.G + hx) * nn;
  return r;
}

} // namespace

ConeConstants mohr_coulomb_cone(double phi, MohrCoulombMatch match) {
  if (match == MohrCoulombMatch::PlaneStrain) {
    const double t = std::tan(phi), d = std::sqrt(9.0 + 12.0 * t * t);
    return {3.0 * t / d, 3.0 / d};
  }
  const double d = std::sqrt(3.0) *
                   (match == MohrCoulombMatch::Outer ? 3.0 - std::sin(phi) : 3.0 + std::sin(phi));
  return {6.0 * std::sin(phi) / d, 6.0 * std::cos(phi) / d};
}

double apex_pressure(const DruckerPragerParameters& p, double cohesion) {
  return p.eta > 0.0 ? p.xi * cohesion / p.eta : std::numeric_limits<double>::infinity();
}

double drucker_prager_yield(const DruckerPragerParameters& p, const Vec6& stress, double alpha) {
  const double J = voigt::tensor_norm(voigt::deviator(stress)) / kSqrt2;
  return J + p.eta * stress.head<3>().sum() / 3.0 - p.xi * (p.cohesion + p.hardening * alpha);
}

StressUpdate3D drucker_prager_update_3d(const DruckerPragerParameters& p, const Vec6& strain,
                                        const MaterialState& committed) {
  const Trial t = trial_state(p, strain, committed);
  const double phi = t.J + p.eta * t.p - p.xi * t.c;
  const bool cutoff = std::isfinite(p.tension_cutoff);
  if (phi <= 0.0 && !(cutoff && t.p > p.tension_cutoff)) {
    StressUpdate3D r;
    r.stress = t.s + t.p * voigt::unit_trace();
    r.tangent = 2.0 * t.G * voigt::deviatoric_projector() +
                t.K * voigt::unit_trace() * voigt::unit_trace().transpose();
    r.state = committed;
    return r;
  }
  if (phi > 0.0) {
    const double dgamma = phi / (t.G + t.K * p.eta * p.eta_bar + p.xi * p.xi * p.hardening);
    const bool inside_apex = t.J - t.G * dgamma >= 0.0;
    const bool below_cutoff = t.p - t.K * p.eta_bar * dgamma <= p.tension_cutoff;
    if (inside_apex && below_cutoff) return cone_return(p, t, dgamma, committed);
    if (!inside_apex && !cutoff) return apex_return(p, t, committed);
  }
  return cutoff_return(p, t, committed);
}

} // namespace mf::materials
