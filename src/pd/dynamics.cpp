#include "meshfree/pd/dynamics.hpp"
#include <algorithm>
#include <cmath>

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

/// y = X + u over the components [lo, hi) (no parallel region when there are none).
void positions(const particles::ParticleSet& q, std::size_t lo, std::size_t hi,
               std::vector<double>& y) {
  if (lo >= hi) return;
  const std::ptrdiff_t first = static_cast<std::ptrdiff_t>(lo), end = static_cast<std::ptrdiff_t>(hi);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = first; k < end; ++k) y[k] = q.X[k] + q.u[k];
}

/// The velocity components the constraints fix, in the order Loading::for_each_fixed visits them.
std::vector<double> fixed_velocities(const Loading& loading, const particles::ParticleSet& q) {
  std::vector<double> v;
  loading.for_each_fixed(q.time, [&](std::size_t k, const Constraint&, double) { v.push_back(q.v[k]); });
  return v;
}

/// The second half kick of a velocity-Verlet step, v += h a with h = dt / 2, when `on`.
struct Kick {
  bool on = false;
  double h = 0.0;
};

/// The forces at the positions y (owned particles and ghosts, ghosts' displacements exchanged)
/// and the accelerations they give; with a kick, the velocities take it in the same pass (one
/// parallel loop instead of two: each loop costs the wake-up of the sleeping threads). A
/// constrained component has zero acceleration, so its velocity is v + h 0, as a kick after the
/// accelerations gives it.
StepReport forces(Model& m, BondState& s, const Loading& loading, const Interactions& x,
                  bool with_energy, const std::vector<double>& y, Kick kick) {
  particles::ParticleSet& q = m.particles;
  const int n = q.owned_count();
  std::vector<double>& f = step_arrays().f;
  std::vector<unsigned char> intact_before;
  if (x.fracture) intact_before = s.intact;
  const ForceReport fr = bond_forces(m, s, y, f, with_energy);
  if (!s.s0.empty()) m.halo.exchange(s.s0.committed); // the ghosts' critical stretch
  loading.add_forces(q.time, f);
  double contact_energy = 0.0;
  if (x.short_range) contact_energy += m.halo.ranks().sum(x.short_range->add_forces(m, y, f));
  if (x.impactors)
    for (Impactor& imp : *x.impactors)
      if (imp.law == Impactor::Law::Penalty) {
        penalty_contact(q, y, imp, f, m.halo.ranks());
        contact_energy += imp.contact_energy;
      }
  const std::vector<double> held = kick.on ? fixed_velocities(loading, q) : std::vector<double>{};
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      q.a[k] = f[k] / q.density[i];
      if (kick.on) q.v[k] += kick.h * q.a[k];
    }
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
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < size; ++k) {
    u_old[k] = q.u[k];
    q.v[k] += 0.5 * dt * q.a[k];
    q.u[k] += dt * q.v[k];
    y[k] = q.X[k] + q.u[k];
  }
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
    std::vector<double>& du = w.du;
    du.resize(size);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < size; ++k) du[k] = q.u[k] - u_old[k];
    work = 0.5 * (loading.power(du, q.volume, t_old) + loading.power(du, q.volume, q.time));
    if (x.fracture) fracture_work = m.halo.ranks().sum(x.fracture->work_over_step(du));
  }
  m.halo.exchange(q.u, 3); // the ghosts' positions, as their owners moved them
  positions(q, pushed ? 0 : size, y.size(), y);
  loading.for_each_fixed(q.time, [&](std::size_t k, const Constraint&, double) {
    y[k] = q.X[k] + q.u[k];
  });
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
