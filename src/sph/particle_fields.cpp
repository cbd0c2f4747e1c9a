#include "meshfree/sph/particle_fields.hpp"
#include <cstddef>
#include <limits>

namespace mf::sph {

// Every member is a registered array: a vector added to the struct and not to for_each_member
// (so not migrated, copied to mirror images nor checkpointed) fails here. std::vector has one
// size whatever it holds.
static_assert(sizeof(ParticleFields) ==
                  particles::registered_fields<ParticleFields>() * sizeof(std::vector<char>),
              "a member of ParticleFields is missing from ParticleFields::for_each_member");

void ParticleFields::add(double density, double energy, double smoothing, bool is_fixed) {
  // Every array gets the particle's values at zero, then those that start elsewhere are set.
  for_each_field([](const particles::FieldInfo& f, auto& a) { a.resize(a.size() + f.components); });
  const std::size_t i = rho.size() - 1;
  rho[i] = density;
  e[i] = energy;
  h[i] = smoothing;
  h_ref[i] = smoothing;
  rho_lo[i] = 0.0;
  rho_hi[i] = std::numeric_limits<double>::infinity();
  light_time[i] = -1.0;
  fixed[i] = is_fixed ? 1 : 0;
  rho_max[i] = density;
}

void ParticleFields::append_copy(int i) {
  const std::size_t k = static_cast<std::size_t>(i);
  for_each_field([k](const particles::FieldInfo& f, auto& a) {
    const std::size_t per = static_cast<std::size_t>(f.components);
    for (std::size_t c = 0; c < per; ++c) {
      const auto value = a[per * k + c]; // read before `a` grows
      a.push_back(value);
    }
  });
  fixed.back() = 1;
}

void ParticleFields::truncate(int n) {
  const std::size_t m = static_cast<std::size_t>(n);
  for_each_field([m](const particles::FieldInfo& f, auto& a) { a.resize(f.components * m); });
}

} // namespace mf::sph
