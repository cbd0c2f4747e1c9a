#include "meshfree/pd/contact.hpp"
#include <cmath>

namespace mf::pd {

void kinematic_contact(particles::ParticleSet& p, Impactor& imp, double dt,
                       const distribution::Ranks& ranks) {
  const int n = p.owned_count();
  double impulse[3] = {0.0, 0.0, 0.0};
  double gain = 0.0; // kinetic energy the particles gain in the exchange (see below)
#pragma omp parallel for schedule(static) reduction(+ : impulse[:3], gain)
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
      // What the exchange adds to the kinetic energy of the full steps that velocity Verlet
      // balances against the trapezoidal work of the forces: m dv . (v^n + dv / 2), v^n =
      // v^{n+1/2} - dt a^n / 2 the velocity at the start of the step (a particle held on a
      // support, pushed back each step by dv = -dt a, gains nothing).
      gain += mass * dv * (p.v[k] - 0.5 * dt * p.a[k] + 0.5 * dv);
      p.v[k] += dv;
      impulse[d] += mass * dv;
    }
  }
  // The particles' momentum gain is the impactor's loss. What the impactor loses in kinetic
  // energy (free) or its drive gives (prescribed, J . V) and the particles do not gain is
  // dissipated; a fixed support gives nothing.
  ranks.sum(impulse, 3);
  gain = ranks.sum(gain);
  const Eigen::Vector3d J(impulse[0], impulse[1], impulse[2]);
  double given = 0.0;
  if (imp.prescribed) {
    given = J.dot(imp.velocity);
    imp.work += given;
  } else if (!imp.fixed) {
    const Eigen::Vector3d before = imp.velocity;
    imp.velocity -= J / imp.mass;
    given = 0.5 * imp.mass * (before.squaredNorm() - imp.velocity.squaredNorm());
  }
  imp.dissipated += given - gain;
  imp.contact_force = -J / dt;
}

void penalty_contact(const particles::ParticleSet& p, const std::vector<double>& y, Impactor& imp,
                     std::vector<double>& force, const distribution::Ranks& ranks) {
  const int n = p.owned_count();
  const double K = imp.stiffness;
  const Eigen::Vector3d c = imp.position, dir = imp.direction;
  const bool sphere = imp.shape == Impactor::Shape::Sphere;
  const double ahead = imp.half_size.dot(dir.cwiseAbs());
  double on_body[3] = {0.0, 0.0, 0.0}, energy = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : on_body[:3], energy)
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d rel(y[3 * i] - c(0), y[3 * i + 1] - c(1), y[3 * i + 2] - c(2));
    double depth;
    Eigen::Vector3d normal;
    if (sphere) {
      // FixIndent::post_force, sphere, side out: dr = r - R, fmag = k dr^2, skipped for dr >= 0.
      const double r = rel.norm();
      if (r >= imp.radius || r == 0.0) continue;
      depth = imp.radius - r;
      normal = rel / r;
    } else {
      // The plane variant on the leading face, within the block's extent.
      if ((rel.cwiseAbs() - imp.half_size).maxCoeff() >= 0.0) continue;
      depth = ahead - rel.dot(dir);
      normal = dir;
    }
    const double f = K * depth * depth;
    for (int d = 0; d < 3; ++d) {
      force[3 * i + d] += f * normal(d);
      on_body[d] += p.volume[i] * f * normal(d);
    }
    energy += p.volume[i] * K * depth * depth * depth / 3.0;
  }
  ranks.sum(on_body, 3);
  imp.contact_force = -Eigen::Vector3d(on_body[0], on_body[1], on_body[2]);
  imp.contact_energy = ranks.sum(energy);
}

double derived_penalty_stiffness(double density, double stable_dt, double spacing) {
  const double C = 2.0 * density / (stable_dt * stable_dt);
  return C / (4.0 * spacing);
}

} // namespace mf::pd
