#include "meshfree/pd/relaxation.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/state_based.hpp"
#include "meshfree/solvers/pd_multigrid_system.hpp"
#include "meshfree/solvers/symmetric_block_system.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

namespace mf::pd {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The loading of a static problem per component (3 per particle): the body force density, and
/// whether the component is held and where. Velocity-constrained components and, in a plane,
/// the out-of-plane ones are held where they are.
struct Statics {
  std::vector<double> b;
  std::vector<unsigned char> held;
  std::vector<double> target;
};

Statics statics(const Model& m, const Loading& loading) {
  const particles::ParticleSet& q = m.particles;
  const double t = q.time;
  const std::size_t size = 3 * static_cast<std::size_t>(q.size());
  Statics st;
  st.b.assign(size, 0.0);
  st.held.assign(size, 0);
  st.target = q.u;
  for (const BodyLoad& load : loading.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const double g = loading.factor(load, k, t);
      for (int d = 0; d < 3; ++d) st.b[3 * load.particles[k] + d] += g * load.density_of(k, d);
    }
  loading.for_each_fixed(t, [&st](std::size_t k, const Constraint& c, double value) {
    st.held[k] = 1;
    if (!c.velocity) st.target[k] = value;
  });
  if (m.plane())
    for (std::size_t k = 2; k < size; k += 3) st.held[k] = 1;
  return st;
}

/// Suspends bond breaking for its lifetime: every critical stretch set to zero and the LAMMPS
/// rule's s0 put aside (the force loop then neither breaks bonds nor renews s0).
class NoBreaking {
public:
  NoBreaking(Model& m, BondState& s, bool active) : m_(m), s_(s), active_(active) {
    if (!active_) return;
    laws_ = m.laws;
    for (materials::BondLaw& law : m.laws) law.critical_stretch = 0.0;
    fold_laws(m);
    s0_ = std::move(s.s0);
    s.s0 = {};
  }
  ~NoBreaking() {
    if (!active_) return;
    m_.laws = std::move(laws_);
    fold_laws(m_);
    s_.s0 = std::move(s0_);
  }
  NoBreaking(const NoBreaking&) = delete;
  NoBreaking& operator=(const NoBreaking&) = delete;

private:
  Model& m_;
  BondState& s_;
  bool active_;
  std::vector<materials::BondLaw> laws_;
  particles::Staged<double> s0_;
};

/// Norms (squared) of the forces of one evaluation, each component's force density times its
/// particle's volume.
struct Norms {
  double residual = 0.0; // free components: bonds plus loads
  double loads = 0.0;    // free components: loads
  double reaction = 0.0; // held components: bonds
  double ratio() const {
    const double external = std::sqrt(std::max(loads, reaction));
    if (external > 0.0) return std::sqrt(residual) / external;
    return residual > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
};

/// Net force density f at the current displacement: the bond forces (pd::bond_forces, or the
/// state-based pd::state_forces) plus
/// `scale` times the body loads on free components, zero on held ones.
Norms net_force(const Model& m, BondState& s, const Statics& st, double scale,
                std::vector<double>& y, std::vector<double>& f) {
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  y.resize(q.X.size());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = q.X[k] + q.u[k];
  if (m.state_based())
    state_forces(m, s, y, f);
  else
    bond_forces(m, s, y, f);
  double residual = 0.0, loads = 0.0, reaction = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : residual, loads, reaction)
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      const double V = q.volume[i];
      if (st.held[k]) {
        reaction += f[k] * V * f[k] * V;
        f[k] = 0.0;
      } else {
        const double load = scale * st.b[k];
        f[k] += load;
        residual += f[k] * V * f[k] * V;
        loads += load * V * load * V;
      }
    }
  return {residual, loads, reaction};
}

/// Fictitious density of every component for a unit step (Kilic & Madenci 2010):
/// lambda_ii >= (1/4) dt^2 sum_j |K_ij| (Gershgorin's bound on the spectrum of D^-1 K, which
/// keeps the central difference stable). The stiffness of the linearised bond force is the
/// block K_ij = c w_ij / |xi_ij| e e^T (j != i) and K_ii = -sum_j K_ij, so that the row sum of
/// component d is at most 2 sum_j c w_ij / |xi_ij| |e_d| (|e_x| + |e_y| + |e_z|), over the
/// intact bonds at the reference directions e.
std::vector<double> fictitious_density(const Model& m, const BondState& s) {
  if (m.state_based()) return state_fictitious_density(m, s);
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  std::vector<double> lambda(3 * static_cast<std::size_t>(n), 0.0);
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const double L = c.length;
    const double e[3] = {(q.X[3 * j] - q.X[3 * i]) / L, (q.X[3 * j + 1] - q.X[3 * i + 1]) / L,
                         (q.X[3 * j + 2] - q.X[3 * i + 2]) / L};
    const double stiffness = m.laws[c.law].c * w / L;
    const double row = std::abs(e[0]) + std::abs(e[1]) + std::abs(e[2]);
    for (int d = 0; d < 3; ++d) lambda[3 * i + d] += 0.5 * stiffness * std::abs(e[d]) * row;
  });
  return lambda;
}

/// Appends the block of bond i-j (i < j) to block row i, and its share to both diagonal blocks.
/// The force on i of the directed bond i -> j is V_i c w_ij (s e), whose derivative at u = 0 is
/// A = V_i c w_ij / |xi| e e^T with respect to u_j and -A with respect to u_i; the matrix of the
/// Newton step is minus that Jacobian. V_i w_ij = V_j w_ji makes it symmetric: the mean of the
/// two ends' values is taken, so that the upper triangle holds the whole of it.
void add_bond(const Model& m, int i, int j, const BondClass& c, const Statics& st,
              solvers::UpperBlockRows& K, std::vector<double>& diagonal) {
  const particles::ParticleSet& q = m.particles;
  const double L = c.length;
  const double e[2] = {(q.X[3 * j] - q.X[3 * i]) / L, (q.X[3 * j + 1] - q.X[3 * i + 1]) / L};
  const double a =
      0.5 * m.laws[c.law].c * (q.volume[i] * c.weight + q.volume[j] * c.weight_partner) / L;
  K.column.push_back(j);
  for (int r = 0; r < 2; ++r)
    for (int col = 0; col < 2; ++col) {
      const double k = a * e[r] * e[col];
      diagonal[4 * i + 2 * r + col] += k;
      diagonal[4 * j + 2 * r + col] += k;
      // Rows and columns of held components are the identity's.
      K.value.push_back(st.held[3 * i + r] || st.held[3 * j + col] ? 0.0 : -k);
    }
}

/// Sorts the off-diagonal slots of block row i by column (a Full bond layout orders its rows by
/// the partners' global ids).
void sort_row(solvers::UpperBlockRows& K, int i) {
  const int first = K.offset[i] + 1, last = static_cast<int>(K.column.size());
  if (std::is_sorted(K.column.begin() + first, K.column.end())) return;
  std::vector<int> order(last - first);
  for (int t = 0; t < last - first; ++t) order[t] = first + t;
  std::sort(order.begin(), order.end(), [&K](int a, int b) { return K.column[a] < K.column[b]; });
  std::vector<int> column;
  std::vector<double> value;
  for (int t : order) {
    column.push_back(K.column[t]);
    value.insert(value.end(), K.value.begin() + 4 * t, K.value.begin() + 4 * t + 4);
  }
  std::copy(column.begin(), column.end(), K.column.begin() + first);
  std::copy(value.begin(), value.end(), K.value.begin() + 4 * first);
}

/// The linearised bond stiffness of a plane body's x and y components (Model::plane), the upper
/// triangle of its 2x2 blocks in one pass over the stored bonds (each pair once from its end of
/// smaller index). Rows and columns of held components are the identity's; a free diagonal entry
/// is raised by 1e-8 of itself.
solvers::UpperBlockRows plane_stiffness(const Model& m, const BondState& s, const Statics& st) {
  const Bonds& b = m.bonds;
  const int n = m.particles.size();
  solvers::UpperBlockRows K;
  K.offset.reserve(n + 1);
  const std::size_t pairs = static_cast<std::size_t>(b.pairs());
  K.column.reserve(n + pairs);
  K.value.reserve(4 * (n + pairs));
  std::vector<double> diagonal(4 * static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    K.column.push_back(i);
    K.value.insert(K.value.end(), 4, 0.0);
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      const int j = b.partner[k];
      if (j > i && s.intact[k]) add_bond(m, i, j, b.classes[b.cls[k]], st, K, diagonal);
    }
    sort_row(K, i);
    K.offset.push_back(static_cast<int>(K.column.size()));
  }
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < 2; ++r)
      for (int col = 0; col < 2; ++col) {
        const bool held = st.held[3 * i + r] || st.held[3 * i + col];
        const double k = diagonal[4 * i + 2 * r + col];
        K.value[4 * static_cast<std::size_t>(K.offset[i]) + 2 * r + col] =
            held ? (r == col ? 1.0 : 0.0) : (r == col ? k * (1.0 + 1e-8) : k);
      }
  return K;
}

/// The rigid motions of a plane body that its held components leave free, orthonormal (two
/// values per particle): the translation along x or y where no particle holds that component,
/// the rotation about the centroid where none holds any.
std::vector<std::vector<double>> free_rigid_modes(const Model& m, const Statics& st) {
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  bool held[2] = {false, false};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d) held[d] = held[d] || st.held[3 * i + d];
  std::vector<std::vector<double>> modes;
  for (int d = 0; d < 2; ++d) {
    if (held[d]) continue;
    modes.emplace_back(2 * static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) modes.back()[2 * i + d] = 1.0 / std::sqrt(double(n));
  }
  if (held[0] || held[1] || n < 2) return modes;
  double c[2] = {0.0, 0.0};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d) c[d] += q.X[3 * i + d] / n;
  std::vector<double> rotation(2 * static_cast<std::size_t>(n));
  double norm = 0.0;
  for (int i = 0; i < n; ++i) {
    rotation[2 * i] = -(q.X[3 * i + 1] - c[1]);
    rotation[2 * i + 1] = q.X[3 * i] - c[0];
    norm += rotation[2 * i] * rotation[2 * i] + rotation[2 * i + 1] * rotation[2 * i + 1];
  }
  for (double& v : rotation) v /= std::sqrt(norm);
  modes.push_back(rotation);
  return modes;
}

/// Removes from v its components along the orthonormal modes.
void remove_modes(const std::vector<std::vector<double>>& modes, std::vector<double>& v) {
  for (const std::vector<double>& r : modes) {
    double dot = 0.0;
    for (std::size_t k = 0; k < v.size(); ++k) dot += r[k] * v[k];
    for (std::size_t k = 0; k < v.size(); ++k) v[k] -= dot * r[k];
  }
}

} // namespace

RelaxReport relax(Model& m, BondState& s, const Loading& loading, const RelaxSettings& settings) {
  const Clock::time_point start = Clock::now();
  NoBreaking guard(m, s, !settings.allow_breaking);
  particles::ParticleSet& q = m.particles;
  const std::size_t size = q.u.size();
  const Statics st = statics(m, loading);
  for (std::size_t k = 0; k < size; ++k)
    if (st.held[k]) q.u[k] = st.target[k];
  const std::vector<double> lambda = fictitious_density(m, s);
  // Components that move: free, with a stiffness to divide by.
  std::vector<unsigned char> moves(size);
  for (std::size_t k = 0; k < size; ++k) moves[k] = !st.held[k] && lambda[k] > 0.0;
  std::vector<double> y, f, f_old, v(size, 0.0);
  Norms norms = net_force(m, s, st, 1.0, y, f);
  RelaxReport r;
  r.residual_ratio = norms.ratio();
  while (!(r.residual_ratio <= settings.tolerance) && std::isfinite(r.residual_ratio) &&
         r.iterations < settings.max_iterations) {
    double c = 0.0;
    if (r.iterations > 0) {
      // Damping from the lowest frequency as a Rayleigh quotient (Kilic & Madenci 2010):
      // c^n = 2 sqrt((u^T K^n u) / (u^T u)) with the local diagonal stiffness
      // K_ii^n = -(F_i^n - F_i^n-1) / (lambda_ii dt v_i^n-1/2), dt = 1; no damping when the
      // quotient is not positive, and kept below 2, where the velocity factor (2 - c) / (2 + c)
      // of the update would change sign.
      double uKu = 0.0, uu = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : uKu, uu)
      for (std::size_t k = 0; k < size; ++k) {
        if (!moves[k]) continue;
        uu += q.u[k] * q.u[k];
        if (v[k] != 0.0) uKu -= q.u[k] * q.u[k] * (f[k] - f_old[k]) / (lambda[k] * v[k]);
      }
      if (uu > 0.0 && uKu > 0.0) c = std::min(2.0 * std::sqrt(uKu / uu), 1.9);
    }
    // Central-difference update with the fictitious density and damping (Kilic & Madenci 2010,
    // dt = 1): v^n+1/2 = ((2 - c^n) v^n-1/2 + 2 F^n / lambda) / (2 + c^n), started by
    // v^1/2 = F^0 / (2 lambda); u^n+1 = u^n + v^n+1/2.
    const bool first = r.iterations == 0;
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k) {
      if (!moves[k]) continue;
      v[k] =
          first ? 0.5 * f[k] / lambda[k] : ((2.0 - c) * v[k] + 2.0 * f[k] / lambda[k]) / (2.0 + c);
      q.u[k] += v[k];
    }
    ++r.iterations;
    f_old.swap(f);
    norms = net_force(m, s, st, 1.0, y, f);
    r.residual_ratio = norms.ratio();
  }
  r.converged = r.residual_ratio <= settings.tolerance;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
  r.seconds = seconds_since(start);
  return r;
}

ExplicitRelaxReport explicit_relax(Model& m, BondState& s, const Loading& loading,
                                   const ExplicitRelaxSettings& settings) {
  MF_REQUIRE(settings.dt > 0.0, "explicit relaxation: the time step must be positive");
  MF_REQUIRE(settings.ramp_time >= 0.0 && settings.damping >= 0.0,
             "explicit relaxation: the ramp time and the damping must not be negative");
  const Clock::time_point start = Clock::now();
  NoBreaking guard(m, s, !settings.allow_breaking);
  particles::ParticleSet& q = m.particles;
  const int n = q.size();
  const std::size_t size = q.u.size();
  const Statics st = statics(m, loading);
  const double dt = settings.dt, c = settings.damping;
  const auto ramp = [&](double t) {
    return settings.ramp_time > 0.0 ? std::min(t / settings.ramp_time, 1.0) : 1.0;
  };
  // Held components move from where they are to their targets along the ramp.
  const std::vector<double> u_start = q.u;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::vector<double> y, f;
  const auto accelerations = [&](double scale) {
    const Norms norms = net_force(m, s, st, scale, y, f);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) q.a[3 * i + d] = f[3 * i + d] / q.density[i];
    return norms;
  };
  double t = 0.0, scale = ramp(0.0);
  Norms norms = accelerations(scale);
  ExplicitRelaxReport r;
  while (r.steps < settings.max_steps) {
    // Velocity Verlet with a -= c v: the first half kick explicit in the damping, the second
    // implicit (v^n+1 = (v^n+1/2 + dt a^n+1 / 2) / (1 + c dt / 2)).
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k) {
      if (st.held[k]) continue;
      q.v[k] += 0.5 * dt * (q.a[k] - c * q.v[k]);
      q.u[k] += dt * q.v[k];
    }
    t += dt;
    scale = ramp(t);
    for (std::size_t k = 0; k < size; ++k)
      if (st.held[k]) {
        const double u =
            scale < 1.0 ? u_start[k] + scale * (st.target[k] - u_start[k]) : st.target[k];
        q.v[k] = (u - q.u[k]) / dt;
        q.u[k] = u;
      }
    norms = accelerations(scale);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k)
      if (!st.held[k]) q.v[k] = (q.v[k] + 0.5 * dt * q.a[k]) / (1.0 + 0.5 * c * dt);
    ++r.steps;
    const double kinetic = kinetic_energy(m);
    r.peak_kinetic = std::max(r.peak_kinetic, kinetic);
    r.kinetic_ratio = r.peak_kinetic > 0.0 ? kinetic / r.peak_kinetic : 0.0;
    // LS-DYNA's convergence test of dynamic relaxation: kinetic energy over its peak, once the
    // loads are fully on; or the residual ratio, when asked for.
    if (scale >= 1.0 && (kinetic <= settings.ke_ratio * r.peak_kinetic ||
                         norms.ratio() <= settings.residual_tolerance)) {
      r.converged = true;
      break;
    }
  }
  if (scale < 1.0) norms = net_force(m, s, st, 1.0, y, f);
  r.residual_ratio = norms.ratio();
  r.time = t;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
  r.seconds = seconds_since(start);
  return r;
}

void set_displacement(Model& m, const std::vector<double>& u) {
  particles::ParticleSet& q = m.particles;
  MF_REQUIRE(u.size() == q.u.size(), "peridynamics: a displacement needs 3 values per particle (",
             q.u.size(), "), got ", u.size());
  q.u = u;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
}

double residual_ratio(Model& m, BondState& s, const Loading& loading) {
  NoBreaking guard(m, s, true);
  const Statics st = statics(m, loading);
  std::vector<double> y, f;
  return net_force(m, s, st, 1.0, y, f).ratio();
}

} // namespace mf::pd

namespace mf::pd {

namespace {

/// The linear solver of the Newton steps: a Cholesky factorisation made once, or conjugate
/// gradients with multigrid, each solve as accurate as the tolerance still asks.
class StepSolver {
public:
  StepSolver(const Model& m, const BondState& s, const Statics& st, bool multigrid) {
    const solvers::UpperBlockRows K = plane_stiffness(m, s, st);
    if (!multigrid) {
      cholesky_ = std::make_unique<solvers::SymmetricBlockSystem>(K, "pd_");
      return;
    }
    const particles::ParticleSet& q = m.particles;
    const std::size_t n = static_cast<std::size_t>(q.size());
    std::vector<double> x(2 * n);
    std::vector<unsigned char> held(2 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 2; ++d) {
        x[2 * i + d] = q.X[3 * i + d];
        held[2 * i + d] = st.held[3 * i + d];
      }
    multigrid_ = std::make_unique<solvers::MultigridBlockSystem>(K, x, held, "pd_");
  }
  /// Solves K du = rhs, where rhs is the residual of ratio `ratio` and `tolerance` the ratio
  /// asked for: an iterative solve stops at half the tolerance's share of rhs, the step's
  /// linear error then leaving half the tolerance (inexact Newton, [Eisenstat & Walker 1996]),
  /// and at 1e-1 at most so that each step gains at least that.
  solvers::SolveReport solve(const std::vector<double>& rhs, double ratio, double tolerance) {
    if (cholesky_) return cholesky_->solve(rhs);
    const double forcing = std::clamp(0.5 * tolerance / ratio, 1e-12, 1e-1);
    return multigrid_->solve(rhs, forcing);
  }
  std::vector<double> solution() const {
    return cholesky_ ? cholesky_->solution() : multigrid_->solution();
  }
  double setup_seconds() const {
    return cholesky_ ? cholesky_->factorisation_seconds() : multigrid_->setup_seconds();
  }

private:
  std::unique_ptr<solvers::SymmetricBlockSystem> cholesky_;
  std::unique_ptr<solvers::MultigridBlockSystem> multigrid_;
};

/// Multigrid when the settings ask for it, or by default from kMultigridFromParticles up or
/// when the options ask for GAMG.
bool multigrid_for(const Model& m, const RelaxSettings& settings) {
  using Solver = RelaxSettings::LinearSolver;
  if (settings.linear_solver != Solver::automatic)
    return settings.linear_solver == Solver::multigrid;
  return m.particles.size() >= kMultigridFromParticles || solvers::multigrid_asked("pd_");
}

} // namespace

RelaxReport solve_statics(Model& m, BondState& s, const Loading& loading,
                          const RelaxSettings& settings) {
  MF_REQUIRE(!m.state_based(), "solve_statics: Newton on the linearised bond stiffness solves "
                               "bond-based bodies; a state-based one relaxes by ADR");
  MF_REQUIRE(m.plane(), "peridynamics: the implicit equilibrium solves plane bodies");
  MF_REQUIRE(m.particles.owned_count() == m.particles.size(),
             "peridynamics: the implicit equilibrium runs on one rank");
  const Clock::time_point start = Clock::now();
  NoBreaking guard(m, s, true);
  particles::ParticleSet& q = m.particles;
  const int n = q.size();
  const Statics st = statics(m, loading);
  for (std::size_t k = 0; k < q.u.size(); ++k)
    if (st.held[k]) q.u[k] = st.target[k];
  std::vector<double> y, f, rhs(2 * static_cast<std::size_t>(n));
  RelaxReport r;
  r.residual_ratio = net_force(m, s, st, 1.0, y, f).ratio();
  std::unique_ptr<StepSolver> K; // made when a step is needed
  // A body that its held components leave free to move rigidly has a stiffness singular but for
  // the diagonal shift: the residual's part along those motions (the bond forces' moment, of
  // the order of the strain squared) would come back multiplied by the shift's inverse, a rigid
  // rotation that unbalances the held loads. The steps are kept free of rigid motion.
  const std::vector<std::vector<double>> rigid = free_rigid_modes(m, st);
  const int most = std::min(settings.max_iterations, 50);
  while (!(r.residual_ratio <= settings.tolerance) && std::isfinite(r.residual_ratio) &&
         r.iterations < most) {
    if (!K) {
      const Clock::time_point assembly = Clock::now();
      K = std::make_unique<StepSolver>(m, s, st, multigrid_for(m, settings));
      r.assembly_seconds = seconds_since(assembly);
    }
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 2; ++d) rhs[2 * i + d] = f[3 * i + d] * q.volume[i];
    remove_modes(rigid, rhs);
    const solvers::SolveReport solved = K->solve(rhs, r.residual_ratio, settings.tolerance);
    r.linear_iterations += solved.iterations;
    r.solver = solved.solver;
    r.factorisation_seconds = K->setup_seconds();
    std::vector<double> du = K->solution();
    remove_modes(rigid, du);
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 2; ++d)
        if (!st.held[3 * i + d]) q.u[3 * i + d] += du[2 * i + d];
    ++r.iterations;
    r.residual_ratio = net_force(m, s, st, 1.0, y, f).ratio();
  }
  r.converged = r.residual_ratio <= settings.tolerance;
  std::fill(q.v.begin(), q.v.end(), 0.0);
  std::fill(q.a.begin(), q.a.end(), 0.0);
  r.seconds = seconds_since(start);
  return r;
}

} // namespace mf::pd
