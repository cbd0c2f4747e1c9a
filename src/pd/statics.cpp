// Static equilibrium by Newton's method (pd/relaxation.hpp, solve_statics): the linearised bond
// stiffness of a plane body assembled once and factorised or solved by multigrid; for a
// state-based body, Newton-Krylov steps whose conjugate gradients take the LPS's tangent by
// central differences of its forces and that bond stiffness as their preconditioner.
#include "meshfree/core/error.hpp"
#include "meshfree/pd/relaxation.hpp"
#include "meshfree/solvers/pd_multigrid_system.hpp"
#include "meshfree/solvers/symmetric_block_system.hpp"
#include "static_loading.hpp"
#include <algorithm>
#include <memory>

namespace mf::pd {

using namespace detail;

namespace {

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

/// The relative residual a Newton step's iterative solve stops at: half the tolerance's share of
/// the residual of ratio `ratio`, the step's linear error then leaving half the tolerance
/// (inexact Newton, [Eisenstat & Walker 1996]), and 1e-1 at most so that each step gains at
/// least that.
double forcing(double ratio, double tolerance) {
  return std::clamp(0.5 * tolerance / ratio, 1e-12, 1e-1);
}

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
  /// asked for: an iterative solve stops at forcing(ratio, tolerance).
  solvers::SolveReport solve(const std::vector<double>& rhs, double ratio, double tolerance) {
    if (cholesky_) return cholesky_->solve(rhs);
    return multigrid_->solve(rhs, forcing(ratio, tolerance));
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

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) sum += a[k] * b[k];
  return sum;
}

/// The tangent of a state-based plane body at its current u applied to v (two values a particle,
/// zero on the held components): minus the central difference of the force (density times
/// volume) along v, with a step of 1e-6 spacings over |v|_inf: a strain far below a preload's,
/// far above the forces' round-off (the equilibria it reaches and ADR's agree to 4.2e-9 of u at
/// a tolerance of 1e-9, test_pd_stage.cpp); v itself on the held components.
void tangent_product(const Model& m, const BondState& s, const Statics& st,
                     const std::vector<double>& v, std::vector<double>& Kv) {
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  double vmax = 0.0;
  for (double x : v) vmax = std::max(vmax, std::abs(x));
  Kv.assign(v.size(), 0.0);
  if (vmax == 0.0) return;
  const double h = 1e-6 * m.spacing / vmax;
  std::vector<double> y(q.X.size()), f[2], w;
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
        y[k] = q.X[k] + q.u[k] + (d < 2 ? (side ? -h : h) * v[2 * i + d] : 0.0);
      }
    state_forces_kept(m, s.intact, s.plastic, y, f[side], w);
  }
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      Kv[2 * i + d] = st.held[k] ? v[2 * i + d] : -(f[0][k] - f[1][k]) * q.volume[i] / (2.0 * h);
    }
}

struct KrylovReport {
  int iterations = 0;
  std::string preconditioner;
};

/// A Newton step of a state-based plane body: K du = rhs by conjugate gradients, K the LPS's
/// tangent (tangent_product), preconditioned by the linearised bond stiffness of the same bonds
/// (`bonds`, whose micromodulus is the body's contact one: the bond-based body of its bulk
/// modulus), the steps kept free of the rigid motions; stopped when the residual has fallen by
/// `forcing`, after 200 iterations or on a direction of no positive curvature.
KrylovReport krylov_step(const Model& m, const BondState& s, const Statics& st, StepSolver& bonds,
                         const std::vector<std::vector<double>>& rigid,
                         const std::vector<double>& rhs, double forcing, std::vector<double>& du) {
  KrylovReport report;
  const auto precondition = [&](const std::vector<double>& r) {
    const solvers::SolveReport solved = bonds.solve(r, 1.0, 2e-10); // multigrid to 1e-10
    report.preconditioner = solved.solver;
    std::vector<double> z = bonds.solution();
    remove_modes(rigid, z);
    return z;
  };
  du.assign(rhs.size(), 0.0);
  std::vector<double> r = rhs, z = precondition(r), p = z, Kp;
  double rz = dot(r, z);
  const double stop = forcing * std::sqrt(dot(rhs, rhs));
  while (report.iterations < 200 && std::sqrt(dot(r, r)) > stop) {
    tangent_product(m, s, st, p, Kp);
    const double curvature = dot(p, Kp);
    if (!(curvature > 0.0)) break;
    const double alpha = rz / curvature;
    for (std::size_t k = 0; k < du.size(); ++k) du[k] += alpha * p[k], r[k] -= alpha * Kp[k];
    ++report.iterations;
    z = precondition(r);
    const double rz_next = dot(r, z), beta = rz_next / rz;
    rz = rz_next;
    for (std::size_t k = 0; k < p.size(); ++k) p[k] = z[k] + beta * p[k];
  }
  return report;
}

} // namespace

RelaxReport solve_statics(Model& m, BondState& s, const Loading& loading,
                          const RelaxSettings& settings) {
  MF_REQUIRE(!m.state_plastic(), "solve_statics: Newton solves elastic state-based bodies; an "
                                 "eps one relaxes by ADR");
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
    std::vector<double> du;
    if (m.state_based()) {
      const KrylovReport step =
          krylov_step(m, s, st, *K, rigid, rhs, forcing(r.residual_ratio, settings.tolerance), du);
      r.linear_iterations += step.iterations;
      r.solver = "conjugate gradients on the LPS tangent, preconditioned by the bond stiffness (" +
                 step.preconditioner + ")";
    } else {
      const solvers::SolveReport solved = K->solve(rhs, r.residual_ratio, settings.tolerance);
      r.linear_iterations += solved.iterations;
      r.solver = solved.solver;
      du = K->solution();
    }
    r.factorisation_seconds = K->setup_seconds();
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
