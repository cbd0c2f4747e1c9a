#include "meshfree/pd/relaxation.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/pd/forces.hpp"
#include "meshfree/solvers/petsc_session.hpp"
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

/// Net force density f at the current displacement: the bond forces (pd::bond_forces) plus
/// `scale` times the body loads on free components, zero on held ones.
Norms net_force(const Model& m, BondState& s, const Statics& st, double scale,
                std::vector<double>& y, std::vector<double>& f) {
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  y.resize(q.X.size());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = q.X[k] + q.u[k];
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

/// The linearised bond stiffness of a plane body's x and y components (Model::plane), as block
/// rows: row i holds i and its bond partners in increasing order, each entry a 2x2 block
/// (row-major, 4 values); rows and columns of held components are the identity's.
struct PlaneStiffness {
  std::vector<int> offset{0};
  std::vector<int> column;
  std::vector<double> block;
};

/// The slot of column j in row i.
long slot(const PlaneStiffness& K, int i, int j) {
  const auto first = K.column.begin() + K.offset[i], last = K.column.begin() + K.offset[i + 1];
  return static_cast<long>(std::lower_bound(first, last, j) - K.column.begin());
}

PlaneStiffness plane_stiffness(const Model& m, const BondState& s, const Statics& st) {
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  std::vector<std::vector<int>> rows(n);
  for (int i = 0; i < n; ++i) rows[i].push_back(i);
  for_each_directed_bond(m, [&](int i, int j, long k, double, const BondClass&) {
    if (s.intact[k]) rows[i].push_back(j);
  });
  PlaneStiffness K;
  for (auto& r : rows) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    K.column.insert(K.column.end(), r.begin(), r.end());
    K.offset.push_back(static_cast<int>(K.column.size()));
  }
  K.block.assign(4 * K.column.size(), 0.0);
  // Directed bond i -> j: the force on i is V_i c w_ij (s e), whose derivative at u = 0 is
  // A = V_i c w_ij / |xi| e e^T with respect to u_j and -A with respect to u_i. The matrix of the
  // Newton step is minus that Jacobian; V_i w_ij = V_j w_ji makes it symmetric.
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const double L = c.length;
    const double e[2] = {(q.X[3 * j] - q.X[3 * i]) / L, (q.X[3 * j + 1] - q.X[3 * i + 1]) / L};
    const double a = q.volume[i] * m.laws[c.law].c * w / L;
    double* ii = &K.block[4 * slot(K, i, i)];
    double* ij = &K.block[4 * slot(K, i, j)];
    for (int r = 0; r < 2; ++r)
      for (int col = 0; col < 2; ++col) {
        ii[2 * r + col] += a * e[r] * e[col];
        ij[2 * r + col] -= a * e[r] * e[col];
      }
  });
  for (int i = 0; i < n; ++i)
    for (int t = K.offset[i]; t < K.offset[i + 1]; ++t) {
      const int j = K.column[t];
      double* b = &K.block[4 * static_cast<std::size_t>(t)];
      for (int r = 0; r < 2; ++r)
        for (int col = 0; col < 2; ++col) {
          const bool held = st.held[3 * i + r] || st.held[3 * j + col];
          if (held)
            b[2 * r + col] = i == j && r == col ? 1.0 : 0.0;
          else if (i == j && r == col)
            b[2 * r + col] *= 1.0 + 1e-8;
        }
    }
  return K;
}

/// The stiffness as a PETSc matrix (one rank: every block column is owned), factorised on its
/// first solve.
std::unique_ptr<solvers::BlockLinearSystem> stiffness_system(const Model& m,
                                                             const PlaneStiffness& K) {
  const int n = m.particles.size();
  solvers::LinearSolverSettings linear;
  linear.multigrid = 2.0 * n >= 2e5;
  if (linear.multigrid)
    for (int i = 0; i < n; ++i)
      linear.coordinates.insert(linear.coordinates.end(),
                                {m.particles.X[3 * i], m.particles.X[3 * i + 1]});
  // Scalar row 2i holds the upper rows of row i's blocks in column order, row 2i + 1 the lower
  // rows (solvers::BlockValueArrays).
  const auto fill = [&K, n](solvers::BlockValueArrays values, std::vector<double>&) {
    for (int i = 0; i < n; ++i) {
      const long first = K.offset[i], count = K.offset[i + 1] - first;
      double* upper = values.diagonal + 4 * first;
      double* lower = upper + 2 * count;
      for (long t = 0; t < count; ++t) {
        const double* b = &K.block[4 * (first + t)];
        upper[2 * t] = b[0], upper[2 * t + 1] = b[1];
        lower[2 * t] = b[2], lower[2 * t + 1] = b[3];
      }
    }
  };
  return std::make_unique<solvers::BlockLinearSystem>(MPI_COMM_SELF, n, solvers::OwnedRange{0, n},
                                                      K.offset, K.column, fill, true, linear);
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
    // loads are fully on.
    if (scale >= 1.0 && kinetic <= settings.ke_ratio * r.peak_kinetic) {
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

RelaxReport solve_statics(Model& m, BondState& s, const Loading& loading,
                          const RelaxSettings& settings) {
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
  const std::unique_ptr<solvers::BlockLinearSystem> K =
      stiffness_system(m, plane_stiffness(m, s, st));
  std::vector<double> y, f, rhs(2 * static_cast<std::size_t>(n));
  RelaxReport r;
  r.residual_ratio = net_force(m, s, st, 1.0, y, f).ratio();
  const int most = std::min(settings.max_iterations, 50);
  while (!(r.residual_ratio <= settings.tolerance) && std::isfinite(r.residual_ratio) &&
         r.iterations < most) {
    for (int i = 0; i < n; ++i)
      for (int d = 0; d < 2; ++d) rhs[2 * i + d] = f[3 * i + d] * q.volume[i];
    const solvers::SolveReport solved = K->solve(rhs);
    r.linear_iterations += solved.iterations;
    r.solver = solved.solver;
    const std::vector<double> du = K->solution();
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
