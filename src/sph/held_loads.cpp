#include "meshfree/sph/held_loads.hpp"
#include "meshfree/core/error.hpp"
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

} // namespace mf::sph
