#include "meshfree/particles/particle_set.hpp"
#include "meshfree/core/error.hpp"

namespace mf::particles {

namespace {
/// The layout of the set's own numbers (time, step, owned_), for the size check below.
struct Scalars {
  double time;
  long step;
  int owned;
};
} // namespace

// Every member of the set is a registered array or one of its numbers: a vector added to the
// struct and not to for_each_member (so not migrated, copied to ghosts nor checkpointed) fails
// here. std::vector has one size whatever it holds.
static_assert(sizeof(ParticleSet) ==
                  registered_fields<ParticleSet>() * sizeof(std::vector<char>) + sizeof(Scalars),
              "a member of ParticleSet is missing from ParticleSet::for_each_member");

int ParticleSet::add(const Vec3& x, double vol, double rho, int mat, int b) {
  MF_ASSERT(owned_ < 0);
  const long next = id.empty() ? 0 : id.back() + 1;
  // Every array gets the particle's values at zero (at rest), then those given are set.
  for_each_field([](const FieldInfo& f, auto& w) { w.resize(w.size() + f.components); });
  const int i = size() - 1;
  for (int d = 0; d < 3; ++d) X[3 * i + d] = x[d];
  volume[i] = vol;
  density[i] = rho;
  mass[i] = rho * vol;
  material[i] = mat;
  body[i] = b;
  id[i] = next;
  return i;
}

int ParticleSet::add_copy(const ParticleSet& from, int source) {
  const std::size_t k = static_cast<std::size_t>(source);
  for_each_member([this, &from, k](const FieldInfo& f, auto m) {
    auto& to = this->*m;
    const auto& w = from.*m; // `to` may be `w`: each value is read before `to` grows
    for (std::size_t c = 0; c < static_cast<std::size_t>(f.components); ++c) {
      const auto value = w[f.components * k + c];
      to.push_back(value);
    }
  });
  return size() - 1;
}

void ParticleSet::drop_ghosts() {
  if (owned_ < 0) return;
  const std::size_t n = static_cast<std::size_t>(owned_);
  for_each_field([n](const FieldInfo& f, auto& w) { w.resize(f.components * n); });
  owned_ = -1;
}

void ParticleSet::drop_ghosts_from(int first) {
  MF_ASSERT(first >= owned_count() && first <= size());
  if (first == owned_count()) return drop_ghosts();
  const std::size_t n = static_cast<std::size_t>(first);
  for_each_field([n](const FieldInfo& f, auto& w) { w.resize(f.components * n); });
}

} // namespace mf::particles
