#include "meshfree/pd/dynamics.hpp"
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

StepReport accelerate(Model& m, BondState& s, const Loading& loading, bool with_energy) {
  return accelerate(m, s, loading, Interactions{}, with_energy);
}

StepReport accelerate(Model& m, BondState& s, const Loading& loading, const Interactions& x,
                      bool with_energy) {
  particles::ParticleSet& q = m.particles;
  m.halo.exchange(q.u, 3); // the ghosts' positions, as their owners moved them
  const int n = q.owned_count();
  std::vector<double> y(q.X.size());
  const std::ptrdiff_t size = static_cast<std::ptrdiff_t>(y.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < size; ++k) y[k] = q.X[k] + q.u[k];
  std::vector<double> f;
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
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) q.a[3 * i + d] = f[3 * i + d] / q.density[i];
  loading.impose(q, q.time, 0.0, nullptr);
  const distribution::Ranks& ranks = m.halo.ranks();
  StepReport r;
  r.broken = ranks.sum(fr.broken);
  r.strain_energy = with_energy ? ranks.sum(fr.strain_energy) : 0.0;
  r.contact_energy = contact_energy;
  if (r.broken > 0 && x.fracture)
    r.fracture_energy = ranks.sum(x.fracture->broken(m, s, intact_before, y));
  return r;
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
  std::vector<double> u_old = q.u;
  // Half kick and drift.
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < size; ++k) {
    q.v[k] += 0.5 * dt * q.a[k];
    q.u[k] += dt * q.v[k];
  }
  const double t_old = q.time;
  q.time += dt;
  ++q.step;
  loading.impose(q, q.time, dt, &u_old);
  // Impactors: a free penalty impactor takes its half kick from the last contact force; each
  // moving one drifts; kinematic ones then push the particles out.
  std::vector<Eigen::Vector3d> start(impactors.size()), force_before(impactors.size());
  for (std::size_t k = 0; k < impactors.size(); ++k) {
    Impactor& imp = impactors[k];
    start[k] = imp.position;
    force_before[k] = imp.contact_force;
    if (imp.law == Impactor::Law::Penalty && imp.free())
      imp.velocity += 0.5 * dt * imp.contact_force / imp.mass;
    if (!imp.fixed) imp.position += dt * imp.velocity;
    if (imp.law == Impactor::Law::Kinematic) kinematic_contact(q, imp, dt, m.halo.ranks());
  }
  std::vector<double> du(size);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < size; ++k) du[k] = q.u[k] - u_old[k];
  // Work of the body loads over the step: the trapezoidal rule on b . du.
  const double work =
      0.5 * (loading.power(du, q.volume, t_old) + loading.power(du, q.volume, q.time));
  const double fracture_work =
      x.fracture ? m.halo.ranks().sum(x.fracture->work_over_step(du)) : 0.0;
  // New accelerations and the second half kick.
  StepReport r = accelerate(m, s, loading, x, with_energy);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < size; ++k) q.v[k] += 0.5 * dt * q.a[k];
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
