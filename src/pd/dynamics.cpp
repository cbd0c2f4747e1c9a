#include "meshfree/pd/dynamics.hpp"
#include "meshfree/pd/spin_barrier.hpp"
#include "meshfree/pd/state_based.hpp"
#include <algorithm>
#include <cmath>
#include <omp.h>
#include <optional>

namespace mf::pd {

void Loading::add_forces(double t, std::vector<double>& f) const {
  for (const BodyLoad& load : loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      const double g = factor(load, k, t);
      for (int d = 0; d < 3; ++d) f[3 * i + d] += g * load.density_of(k, d);
    }
}

double Loading::power(const std::vector<double>& du, const std::vector<double>& volume,
                      double t) const {
  double w = 0.0;
  for (const BodyLoad& load : loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      const double g = factor(load, k, t);
      for (int d = 0; d < 3; ++d) w += g * load.density_of(k, d) * volume[i] * du[3 * i + d];
    }
  return w;
}

void Loading::impose(particles::ParticleSet& q, double t, double dt,
                     const std::vector<double>* u_before) const {
  for_each_fixed(t, [&](std::size_t k, const Constraint& c, double value) {
    q.a[k] = 0.0;
    if (!u_before) return;
    if (c.velocity) {
      q.v[k] = value;
    } else {
      q.v[k] = (value - (*u_before)[k]) / dt;
      q.u[k] = value;
    }
  });
}

void Loading::keep_velocities(particles::ParticleSet& q, double t) const {
  for (const Constraint& c : constraints)
    if (c.velocity) {
      const double f = factor(c.function, t);
      for (int i : c.particles)
        for (int d = 0; d < 3; ++d)
          if (c.fixed[d]) q.v[3 * i + d] = c.value[d] * f;
    }
}

namespace {

/// The arrays a step works in, kept from one step to the next so that a step neither allocates
/// nor zeroes them.
struct StepArrays {
  std::vector<double> y, u_old, du, f;
};

StepArrays& step_arrays() {
  thread_local StepArrays w;
  return w;
}

// The loops below are work-sharing loops of the enclosing parallel region (nowait: the caller
// waits for all where the next phase needs it).

/// The first half kick and the drift of the components [0, size), keeping u_old and computing
/// the positions y = X + u they give.
void kick_and_drift(particles::ParticleSet& q, double dt, std::size_t size,
                    std::vector<double>& u_old, std::vector<double>& y) {
#pragma omp for schedule(static) nowait
  for (std::size_t k = 0; k < size; ++k) {
    u_old[k] = q.u[k];
    q.v[k] += 0.5 * dt * q.a[k];
    q.u[k] += dt * q.v[k];
    y[k] = q.X[k] + q.u[k];
  }
}

/// du = u - u_old over the components [0, du.size()).
void increments(const particles::ParticleSet& q, const std::vector<double>& u_old,
                std::vector<double>& du) {
  const std::size_t size = du.size();
#pragma omp for schedule(static) nowait
  for (std::size_t k = 0; k < size; ++k) du[k] = q.u[k] - u_old[k];
}

/// The body loads' work over a step from t_old to q.time: the trapezoidal rule on b . du.
double load_work(const Loading& loading, const particles::ParticleSet& q,
                 const std::vector<double>& du, double t_old) {
  return 0.5 * (loading.power(du, q.volume, t_old) + loading.power(du, q.volume, q.time));
}

/// The second half kick of a velocity-Verlet step, v += h a with h = dt / 2, when `on`.
struct Kick {
  bool on = false;
  double h = 0.0;
};

/// a = f / density of the owned particles, and with a kick v += h a in the same pass (one loop
/// instead of two).
void accelerations(particles::ParticleSet& q, const std::vector<double>& f, Kick kick) {
  const int n = q.owned_count();
#pragma omp for schedule(static) nowait
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      q.a[k] = f[k] / q.density[i];
      if (kick.on) q.v[k] += kick.h * q.a[k];
    }
}

/// y = X + u over the components [lo, hi) (no parallel region when there are none).
void positions(const particles::ParticleSet& q, std::size_t lo, std::size_t hi,
               std::vector<double>& y) {
  if (lo >= hi) return;
  const std::ptrdiff_t first = static_cast<std::ptrdiff_t>(lo),
                       end = static_cast<std::ptrdiff_t>(hi);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = first; k < end; ++k) y[k] = q.X[k] + q.u[k];
}

/// y = X + u of the components the constraints fix (their u was just imposed).
void fixed_positions(const Loading& loading, const particles::ParticleSet& q,
                     std::vector<double>& y) {
  loading.for_each_fixed(q.time,
                         [&](std::size_t k, const Constraint&, double) { y[k] = q.X[k] + q.u[k]; });
}

/// The velocity components the constraints fix, in the order Loading::for_each_fixed visits them.
std::vector<double> fixed_velocities(const Loading& loading, const particles::ParticleSet& q) {
  std::vector<double> v;
  loading.for_each_fixed(q.time,
                         [&](std::size_t k, const Constraint&, double) { v.push_back(q.v[k]); });
  return v;
}

/// Body loads, then the short-range contact and penalty impactors' forces added to f (after the
/// bond forces, as LAMMPS adds fix indent's in post_force); their potential energy.
double add_interactions(Model& m, const Loading& loading, const Interactions& x,
                        const std::vector<double>& y, std::vector<double>& f) {
  particles::ParticleSet& q = m.particles;
  loading.add_forces(q.time, f);
  double contact_energy = 0.0;
  if (x.short_range) contact_energy += m.halo.ranks().sum(x.short_range->add_forces(m, y, f));
  if (x.impactors)
    for (Impactor& imp : *x.impactors)
      if (imp.law == Impactor::Law::Penalty) {
        penalty_contact(q, y, imp, f, m.halo.ranks());
        contact_energy += imp.contact_energy;
      }
  return contact_energy;
}

/// What follows the accelerations: constrained components get zero acceleration, and with a kick
/// a constrained velocity is the `held` one plus h 0, as a kick after the accelerations gives it;
/// the report, summed over the ranks.
StepReport conclude(Model& m, BondState& s, const Loading& loading, const Interactions& x,
                    const ForceReport& fr, double contact_energy, bool with_energy, Kick kick,
                    const std::vector<double>& held,
                    const std::vector<unsigned char>& intact_before, const std::vector<double>& y) {
  particles::ParticleSet& q = m.particles;
  loading.impose(q, q.time, 0.0, nullptr);
  if (kick.on) {
    std::size_t e = 0;
    loading.for_each_fixed(q.time, [&](std::size_t k, const Constraint&, double) {
      q.v[k] = held[e++] + kick.h * q.a[k];
    });
  }
  const distribution::Ranks& ranks = m.halo.ranks();
  StepReport r;
  r.broken = ranks.sum(fr.broken);
  r.strain_energy = with_energy ? ranks.sum(fr.strain_energy) : 0.0;
  r.contact_energy = contact_energy;
  if (r.broken > 0 && x.fracture)
    r.fracture_energy = ranks.sum(x.fracture->broken(m, s, intact_before, y));
  return r;
}

/// The forces at the positions y (owned particles and ghosts, ghosts' displacements exchanged)
/// and the accelerations they give, with the kick if on: each in a parallel region of its own.
StepReport forces(Model& m, BondState& s, const Loading& loading, const Interactions& x,
                  bool with_energy, const std::vector<double>& y, Kick kick) {
  particles::ParticleSet& q = m.particles;
  std::vector<double>& f = step_arrays().f;
  std::vector<unsigned char> intact_before;
  if (x.fracture) intact_before = s.intact;
  const ForceReport fr = m.state_based() ? state_forces(m, s, y, f, with_energy)
                                         : bond_forces(m, s, y, f, with_energy);
  if (!s.s0.empty()) m.halo.exchange(s.s0.committed); // the ghosts' critical stretch
  const double contact_energy = add_interactions(m, loading, x, y, f);
  const std::vector<double> held = kick.on ? fixed_velocities(loading, q) : std::vector<double>{};
#pragma omp parallel
  accelerations(q, f, kick);
  return conclude(m, s, loading, x, fr, contact_energy, with_energy, kick, held, intact_before, y);
}

/// Whether a step can run as one parallel region whose threads wait for each other by spinning
/// (advance_in_one_region): nothing in it has parallel loops of its own (impactors, short-range
/// contact, the two passes of a state-based body) or exchanges with other ranks.
bool one_region(const Model& m, const Interactions& x) {
  return (!x.impactors || x.impactors->empty()) && !x.short_range && m.halo.ranks().serial() &&
         !m.state_based();
}

/// advance() without impactors, short-range contact or other ranks, as one parallel region: its
/// threads wake once per step, and wait for each other between the phases by spinning
/// (pd::SpinBarrier), one thread doing the serial parts. The same operations as advance()'s
/// other path, in the same order, so the same results bit for bit.
StepReport advance_in_one_region(Model& m, BondState& s, const Loading& loading,
                                 const Interactions& x, double dt, bool with_energy) {
  particles::ParticleSet& q = m.particles;
  const std::size_t size = 3 * static_cast<std::size_t>(q.owned_count());
  StepArrays& w = step_arrays();
  w.u_old.resize(q.u.size());
  w.y.resize(q.X.size());
  const bool need_du = !loading.loads.empty() || x.fracture;
  w.du.resize(need_du ? size : 0);
  const double t_old = q.time;
  const Kick kick{true, 0.5 * dt};
  double work = 0.0, fracture_work = 0.0, contact_energy = 0.0;
  std::vector<unsigned char> intact_before;
  std::vector<double> held;
  std::optional<BondForcePass> pass;
  ForceReport fr;
  SpinBarrier barrier;
#pragma omp parallel
  {
    const bool serial = omp_get_thread_num() == 0;
    kick_and_drift(q, dt, size, w.u_old, w.y);
    barrier.wait();
    if (serial) {
      std::copy(q.u.begin() + size, q.u.end(), w.u_old.begin() + size);
      q.time += dt;
      ++q.step;
      loading.impose(q, q.time, dt, &w.u_old);
    }
    barrier.wait();
    if (need_du) {
      increments(q, w.u_old, w.du);
      barrier.wait();
    }
    if (serial) {
      if (need_du) {
        work = load_work(loading, q, w.du, t_old);
        if (x.fracture) fracture_work = x.fracture->work_over_step(w.du);
      }
      fixed_positions(loading, q, w.y);
      if (x.fracture) intact_before = s.intact;
      pass.emplace(m, s, w.y, w.f, with_energy);
    }
    barrier.wait();
    pass->rows();
    barrier.wait();
    pass->finish();
    barrier.wait();
    if (serial) {
      fr = pass->report();
      contact_energy = add_interactions(m, loading, x, w.y, w.f);
      held = fixed_velocities(loading, q);
    }
    barrier.wait();
    accelerations(q, w.f, kick);
  }
  StepReport r =
      conclude(m, s, loading, x, fr, contact_energy, with_energy, kick, held, intact_before, w.y);
  loading.keep_velocities(q, q.time);
  r.external_work = work;
  r.fracture_work = fracture_work;
  return r;
}

} // namespace

StepReport accelerate(Model& m, BondState& s, const Loading& loading, bool with_energy) {
  return accelerate(m, s, loading, Interactions{}, with_energy);
}

StepReport accelerate(Model& m, BondState& s, const Loading& loading, const Interactions& x,
                      bool with_energy) {
  particles::ParticleSet& q = m.particles;
  m.halo.exchange(q.u, 3); // the ghosts' positions, as their owners moved them
  std::vector<double>& y = step_arrays().y;
  y.resize(q.X.size());
  positions(q, 0, y.size(), y);
  return forces(m, s, loading, x, with_energy, y, Kick{});
}

StepReport advance(Model& m, BondState& s, const Loading& loading, std::vector<Impactor>& impactors,
                   double dt, bool with_energy) {
  Interactions x;
  x.impactors = &impactors;
  return advance(m, s, loading, x, dt, with_energy);
}

StepReport advance(Model& m, BondState& s, const Loading& loading, const Interactions& x, double dt,
                   bool with_energy) {
  if (one_region(m, x)) return advance_in_one_region(m, s, loading, x, dt, with_energy);
  particles::ParticleSet& q = m.particles;
  std::vector<Impactor> none;
  std::vector<Impactor>& impactors = x.impactors ? *x.impactors : none;
  const std::size_t size = 3 * static_cast<std::size_t>(q.owned_count());
  StepArrays& w = step_arrays();
  w.u_old.resize(q.u.size());
  w.y.resize(q.X.size());
  std::vector<double>& u_old = w.u_old;
  std::vector<double>& y = w.y;
  // Half kick and drift, and the positions they give (those of components that a constraint, a
  // kinematic impactor or the halo moves next are refreshed below).
#pragma omp parallel
  kick_and_drift(q, dt, size, u_old, y);
  std::copy(q.u.begin() + size, q.u.end(), u_old.begin() + size);
  const double t_old = q.time;
  q.time += dt;
  ++q.step;
  loading.impose(q, q.time, dt, &u_old);
  // Impactors: a free penalty impactor takes its half kick from the last contact force; each
  // moving one drifts; kinematic ones then push the particles out.
  std::vector<Eigen::Vector3d> start(impactors.size()), force_before(impactors.size());
  bool pushed = false;
  for (std::size_t k = 0; k < impactors.size(); ++k) {
    Impactor& imp = impactors[k];
    start[k] = imp.position;
    force_before[k] = imp.contact_force;
    if (imp.law == Impactor::Law::Penalty && imp.free())
      imp.velocity += 0.5 * dt * imp.contact_force / imp.mass;
    if (!imp.fixed) imp.position += dt * imp.velocity;
    if (imp.law == Impactor::Law::Kinematic) {
      kinematic_contact(q, imp, dt, m.halo.ranks());
      pushed = true;
    }
  }
  // Work of the body loads over the step (the trapezoidal rule on b . du) and of the bonds broken
  // before it: both need the displacement increments, and there are none without loads or the
  // fracture account.
  double work = 0.0, fracture_work = 0.0;
  if (!loading.loads.empty() || x.fracture) {
    w.du.resize(size);
#pragma omp parallel
    increments(q, u_old, w.du);
    work = load_work(loading, q, w.du, t_old);
    if (x.fracture) fracture_work = m.halo.ranks().sum(x.fracture->work_over_step(w.du));
  }
  m.halo.exchange(q.u, 3); // the ghosts' positions, as their owners moved them
  positions(q, pushed ? 0 : size, y.size(), y);
  fixed_positions(loading, q, y);
  // New accelerations and the second half kick.
  StepReport r = forces(m, s, loading, x, with_energy, y, Kick{true, 0.5 * dt});
  for (std::size_t k = 0; k < impactors.size(); ++k) {
    Impactor& imp = impactors[k];
    if (imp.law != Impactor::Law::Penalty) continue;
    if (imp.free()) imp.velocity += 0.5 * dt * imp.contact_force / imp.mass;
    // The drive holds a prescribed impactor against the contact force F: its work on the body
    // over the step is -F . dx (trapezoidal rule).
    if (imp.prescribed)
      imp.work -= 0.5 * (force_before[k] + imp.contact_force).dot(imp.position - start[k]);
  }
  loading.keep_velocities(q, q.time);
  r.external_work = m.halo.ranks().sum(work);
  r.fracture_work = fracture_work;
  return r;
}

double kinetic_energy(const Model& m) {
  const particles::ParticleSet& p = m.particles;
  double e = 0.0;
  for (int i : p.owned()) {
    const double v2 =
        p.v[3 * i] * p.v[3 * i] + p.v[3 * i + 1] * p.v[3 * i + 1] + p.v[3 * i + 2] * p.v[3 * i + 2];
    e += 0.5 * p.density[i] * p.volume[i] * v2;
  }
  return m.halo.ranks().sum(e);
}

} // namespace mf::pd
