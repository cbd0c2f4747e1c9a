#include "meshfree/sph/held_loads.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/neighbours.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/state.hpp"
#include <algorithm>
#include <cmath>

namespace mf::sph {

double face_area(const particles::ParticleSet& P, int i, int dim) {
  const double volume = P.mass[i] / P.density[i];
  return volume / std::pow(volume, 1.0 / dim);
}

SurfaceForce traction_force(const Hydro& h, const std::string& name,
                            const std::vector<int>& particles, const double traction[3]) {
  SurfaceForce out;
  out.name = name;
  for (const int i : particles) {
    if (i < 0 || i >= h.particles.owned_count())
      fail("SPH surface force '", name, "': particle ", i, " is not an owned particle");
    if (h.fields.fixed[i]) continue;
    const double area = face_area(h.particles, i, h.dim);
    out.particles.push_back(i);
    for (int d = 0; d < 3; ++d) out.force.push_back(traction[d] * area);
  }
  return out;
}

void hold_stress(TransmittingBoundary& b, const std::vector<materials::Vec6>& sigma_of_particle) {
  b.static_force.assign(3 * b.particles.size(), 0.0);
  const double* n = b.normal;
  for (std::size_t k = 0; k < b.particles.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(b.particles[k]);
    if (i >= sigma_of_particle.size())
      fail("transmitting boundary '", b.name, "': no stress given for its particle ", i);
    const materials::Vec6& s = sigma_of_particle[i];
    // t = sigma . n with the Voigt order xx yy zz yz xz xy.
    const double t[3] = {s(0) * n[0] + s(5) * n[1] + s(4) * n[2],
                         s(5) * n[0] + s(1) * n[1] + s(3) * n[2],
                         s(4) * n[0] + s(3) * n[1] + s(2) * n[2]};
    for (int d = 0; d < 3; ++d) b.static_force[3 * k + d] = t[d] * b.area[k];
  }
}

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
    for (long k = h.pairs.offset[i]; k < h.pairs.offset[i + 1]; ++k) {
      const int j = h.pairs.partner[k];
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

} // namespace mf::sph
