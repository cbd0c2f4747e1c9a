#include "meshfree/sph/particle_fields.hpp"
#include <cstddef>

namespace mf::sph {

void ParticleFields::add(double density, double energy, double smoothing, bool is_fixed) {
  rho.push_back(density);
  e.push_back(energy);
  h.push_back(smoothing);
  h_ref.push_back(smoothing);
  light_time.push_back(-1.0);
  fixed.push_back(is_fixed ? 1 : 0);
  held_axes.push_back(0);
  for (int k = 0; k < 6; ++k) {
    S.push_back(0.0);
    back_stress.push_back(0.0);
  }
  alpha.push_back(0.0);
  rho_max.push_back(density);
  damage.push_back(0.0);
  strain_rate.push_back(0.0);
  failed.push_back(0);
  p.push_back(0.0);
  c.push_back(0.0);
}

void ParticleFields::append_copy(int i) {
  const std::size_t k = static_cast<std::size_t>(i);
  for_each_array([k](auto& a, int per) {
    for (std::size_t c = 0; c < static_cast<std::size_t>(per); ++c) {
      const auto value = a[per * k + c]; // read before `a` grows
      a.push_back(value);
    }
  });
  fixed.back() = 1;
}

void ParticleFields::truncate(int n) {
  const std::size_t m = static_cast<std::size_t>(n);
  for_each_array([m](auto& a, int per) { a.resize(per * m); });
}

} // namespace mf::sph
