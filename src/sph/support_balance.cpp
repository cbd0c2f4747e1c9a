#include "meshfree/sph/support_balance.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/held_loads.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
#include <algorithm>

namespace mf::sph {

std::vector<double> out_of_balance(Hydro& h) {
  update_state(h);
  refresh_neighbours(h);
  Rates r;
  compute_rates(h, r);
  const particles::ParticleSet& P = h.particles;
  std::vector<double> f(3 * static_cast<std::size_t>(P.owned_count()));
  for (const int i : P.owned())
    for (int d = 0; d < 3; ++d) f[3 * i + d] = P.mass[i] * r.dv[3 * i + d];
  return f;
}

std::vector<int> within_reach(Hydro& h, const std::vector<int>& layer) {
  refresh_neighbours(h);
  const particles::ParticleSet& P = h.particles;
  const ParticleFields& F = h.fields;
  const int owned = P.owned_count();
  std::vector<char> in(owned, 0);
  for (const int i : layer) {
    MF_REQUIRE(i >= 0 && i < owned, "within_reach: particle ", i, " is not owned");
    in[i] = 1;
    for (long k = h.neighbours.pairs.offset[i]; k < h.neighbours.pairs.offset[i + 1]; ++k) {
      const int j = h.neighbours.pairs.partner[k];
      if (j >= owned) continue;
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double dx = P.X[3 * i + d] + P.u[3 * i + d] - P.X[3 * j + d] - P.u[3 * j + d];
        r2 += dx * dx;
      }
      if (r2 < (F.h[i] + F.h[j]) * (F.h[i] + F.h[j])) in[j] = 1;
    }
  }
  std::vector<int> out;
  for (int i = 0; i < owned; ++i)
    if (in[i]) out.push_back(i);
  return out;
}

SurfaceForce balancing_force(Hydro& h, const std::string& name, const std::vector<int>& particles,
                             bool take_resultant) {
  const particles::ParticleSet& P = h.particles;
  const std::vector<double> f = out_of_balance(h);
  const int owned = P.owned_count();
  std::vector<char> listed(owned, 0);
  SurfaceForce out;
  out.name = name;
  double listed_mass = 0.0;
  for (const int i : particles) {
    if (i < 0 || i >= owned)
      fail("SPH balancing force '", name, "': particle ", i, " is not an owned particle");
    if (h.fields.fixed[i] || listed[i]) continue;
    listed[i] = 1;
    listed_mass += P.mass[i];
    out.particles.push_back(i);
    for (int d = 0; d < 3; ++d) out.force.push_back(-f[3 * static_cast<std::size_t>(i) + d]);
  }
  if (take_resultant && listed_mass > 0.0) {
    double rest[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < owned; ++i)
      if (!listed[i])
        for (int d = 0; d < 3; ++d) rest[d] += f[3 * static_cast<std::size_t>(i) + d];
    for (std::size_t k = 0; k < out.particles.size(); ++k)
      for (int d = 0; d < 3; ++d)
        out.force[3 * k + d] -= rest[d] * P.mass[out.particles[k]] / listed_mass;
  }
  return out;
}

double largest_force(const Hydro& h, const std::vector<materials::Vec6>& sigma) {
  double f = 0.0;
  const particles::ParticleSet& P = h.particles;
  for (std::size_t i = 0; i < sigma.size(); ++i)
    f = std::max(f, sigma[i].cwiseAbs().maxCoeff() * face_area(P, static_cast<int>(i), h.dim));
  for (std::size_t c = 0; c < h.conditions.size(); ++c)
    f = std::max(f, h.conditions[c].largest_held_force());
  const double g = Vec3(h.body.gravity[0], h.body.gravity[1], h.body.gravity[2]).norm();
  for (int i = 0; i < P.owned_count(); ++i) f = std::max(f, P.mass[i] * g);
  return f;
}

double worst_out_of_balance(Hydro& h) {
  const std::vector<double> ob = out_of_balance(h);
  double worst = 0.0;
  for (int i = 0; i < h.particles.owned_count(); ++i)
    worst = std::max(worst, Vec3(ob[3 * i], ob[3 * i + 1], ob[3 * i + 2]).norm());
  return worst;
}

RestBalance hold_at_rest(Hydro& h, const std::vector<materials::Vec6>& sigma,
                         const std::vector<int>& held, const std::vector<int>& balanced) {
  std::vector<materials::Vec6> of_particle(h.particles.size(), materials::Vec6::Zero());
  std::copy(sigma.begin(), sigma.end(), of_particle.begin());
  const std::vector<TransmittingBoundary*> boundaries =
      h.conditions.of_kind<TransmittingBoundary>();
  for (int b : held) hold_stress(*boundaries[b], of_particle);
  const double scale = std::max(largest_force(h, sigma), 1e-300);
  RestBalance r;
  r.before = worst_out_of_balance(h) / scale;
  h.conditions.add(balancing_force(h, "transfer_balance", balanced));
  r.after = worst_out_of_balance(h) / scale;
  return r;
}

} // namespace mf::sph
