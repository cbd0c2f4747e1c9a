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
  const auto copy = [k](auto& a, std::size_t per) {
    for (std::size_t c = 0; c < per; ++c) {
      const auto value = a[per * k + c];
      a.push_back(value);
    }
  };
  copy(S, 6), copy(back_stress, 6);
  for (auto* a :
       {&rho, &e, &h, &h_ref, &light_time, &alpha, &rho_max, &damage, &strain_rate, &p, &c})
    copy(*a, 1);
  copy(failed, 1);
  fixed.push_back(1);
}

void ParticleFields::truncate(int n) {
  const std::size_t m = static_cast<std::size_t>(n);
  S.resize(6 * m), back_stress.resize(6 * m);
  for (auto* a :
       {&rho, &e, &h, &h_ref, &light_time, &alpha, &rho_max, &damage, &strain_rate, &p, &c})
    a->resize(m);
  fixed.resize(m), failed.resize(m);
}

} // namespace mf::sph
