#include "meshfree/pd/dynamics.hpp"
#include <cmath>

namespace mf::pd {

namespace {

/// Applies the prescribed components at time t: displacement constraints set u (and the
/// velocity that moved them there from u_before over dt), velocity constraints set v;
/// accelerations of constrained components are zero. Without u_before only the accelerations
/// are set.
void impose(const Loading& loading, particles::ParticleSet& q, double t, double dt,
            const std::vector<double>* u_before) {
  loading.for_each_fixed(t, [&](std::size_t k, const Constraint& c, double value) {
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

/// Kinematic contact of one impactor with the owned particles at their current positions; the
/// momentum they gain is summed over the ranks.
void contact(particles::ParticleSet& p, Impactor& imp, double dt,
             const distribution::Ranks& ranks) {
  const int n = p.owned_count();
  double impulse[3] = {0.0, 0.0, 0.0};
#pragma omp parallel for schedule(static) reduction(+ : impulse[:3])
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d y(p.X[3 * i] + p.u[3 * i], p.X[3 * i + 1] + p.u[3 * i + 1],
                      p.X[3 * i + 2] + p.u[3 * i + 2]);
    const Eigen::Vector3d rel = y - imp.position;
    Eigen::Vector3d target;
    if (imp.shape == Impactor::Shape::Sphere) {
      const double r = rel.norm();
      if (r >= imp.radius || r == 0.0) continue;
      target = imp.position + rel * (imp.radius / r);
    } else {
      if ((rel.cwiseAbs() - imp.half_size).maxCoeff() >= 0.0) continue;
      // Onto the leading face: the face whose outward normal is the impact direction.
      const double ahead = imp.half_size.dot(imp.direction.cwiseAbs());
      target = y + (ahead - rel.dot(imp.direction)) * imp.direction;
    }
    const double mass = p.density[i] * p.volume[i];
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      const double moved = target(d) - y(d);
      p.u[k] += moved;
      const double dv = moved / dt;
      p.v[k] += dv;
      impulse[d] += mass * dv;
    }
  }
  // The particles' momentum gain is the impactor's loss.
  ranks.sum(impulse, 3);
  const Eigen::Vector3d J(impulse[0], impulse[1], impulse[2]);
  if (!imp.fixed) imp.velocity -= J / imp.mass;
  imp.contact_force = -J / dt;
}

} // namespace

StepReport accelerate(Model& m, BondState& s, const Loading& loading, bool with_energy) {
  particles::ParticleSet& q = m.particles;
  m.halo.exchange(q.u, 3); // the ghosts' positions, as their owners moved them
  const int n = q.owned_count();
  std::vector<double> y(q.X.size());
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = q.X[k] + q.u[k];
  std::vector<double> f;
  const ForceReport fr = bond_forces(m, s, y, f, with_energy);
  if (!s.s0.empty()) m.halo.exchange(s.s0.committed); // the ghosts' critical stretch
  for (const BodyLoad& load : loading.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const int i = load.particles[k];
      const double g = loading.factor(load, k, q.time);
      for (int d = 0; d < 3; ++d) f[3 * i + d] += g * load.density_of(k, d);
    }
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) q.a[3 * i + d] = f[3 * i + d] / q.density[i];
  impose(loading, q, q.time, 0.0, nullptr);
  const distribution::Ranks& ranks = m.halo.ranks();
  StepReport r;
  r.broken = ranks.sum(fr.broken);
  r.strain_energy = with_energy ? ranks.sum(fr.strain_energy) : 0.0;
  return r;
}

StepReport advance(Model& m, BondState& s, const Loading& loading, std::vector<Impactor>& impactors,
                   double dt, bool with_energy) {
  particles::ParticleSet& q = m.particles;
  const std::size_t size = 3 * static_cast<std::size_t>(q.owned_count());
  // Work of the body loads over the step: the trapezoidal rule on b . du.
  double work = 0.0;
  const auto load_power = [&](const std::vector<double>& du, double t) {
    double w = 0.0;
    for (const BodyLoad& load : loading.loads)
      for (std::size_t k = 0; k < load.particles.size(); ++k) {
        const int i = load.particles[k];
        const double g = loading.factor(load, k, t);
        for (int d = 0; d < 3; ++d)
          w += g * load.density_of(k, d) * m.particles.volume[i] * du[3 * i + d];
      }
    return w;
  };
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
  impose(loading, q, q.time, dt, &u_old);
  for (Impactor& imp : impactors) {
    imp.position += dt * imp.velocity;
    contact(q, imp, dt, m.halo.ranks());
  }
  std::vector<double> du(size);
  for (std::size_t k = 0; k < size; ++k) du[k] = q.u[k] - u_old[k];
  work += 0.5 * (load_power(du, t_old) + load_power(du, q.time));
  // New accelerations and the second half kick.
  StepReport r = accelerate(m, s, loading, with_energy);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < size; ++k) q.v[k] += 0.5 * dt * q.a[k];
  for (const Constraint& c : loading.constraints) // prescribed velocities stay as prescribed
    if (c.velocity) {
      const double f = loading.factor(c.function, q.time);
      for (int i : c.particles)
        for (int d = 0; d < 3; ++d)
          if (c.fixed[d]) q.v[3 * i + d] = c.value[d] * f;
    }
  r.external_work = m.halo.ranks().sum(work);
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
