#include "meshfree/particles/particle_set.hpp"
#include "meshfree/core/error.hpp"

namespace mf::particles {

int ParticleSet::add(const Vec3& x, double vol, double rho, int mat, int b) {
  MF_ASSERT(owned_ < 0);
  X.insert(X.end(), {x.x(), x.y(), x.z()});
  volume.push_back(vol);
  density.push_back(rho);
  mass.push_back(rho * vol);
  material.push_back(mat);
  body.push_back(b);
  id.push_back(id.empty() ? 0 : id.back() + 1);
  u.insert(u.end(), 3, 0.0);
  v.insert(v.end(), 3, 0.0);
  a.insert(a.end(), 3, 0.0);
  return size() - 1;
}

int ParticleSet::add_ghost(const ParticleSet& from, int source) {
  if (owned_ < 0) owned_ = size();
  const std::size_t k = 3 * static_cast<std::size_t>(source);
  const auto copy3 = [k](std::vector<double>& to, const std::vector<double>& w) {
    const double c[3] = {w[k], w[k + 1], w[k + 2]}; // `to` may be `w`: read before growing it
    to.insert(to.end(), c, c + 3);
  };
  copy3(X, from.X);
  copy3(u, from.u);
  copy3(v, from.v);
  copy3(a, from.a);
  const double vol = from.volume[source], rho = from.density[source], m = from.mass[source];
  const int mat = from.material[source], b = from.body[source];
  const long i = from.id[source];
  volume.push_back(vol);
  density.push_back(rho);
  mass.push_back(m);
  material.push_back(mat);
  body.push_back(b);
  id.push_back(i);
  return size() - 1;
}

void ParticleSet::drop_ghosts() {
  if (owned_ < 0) return;
  const std::size_t n = static_cast<std::size_t>(owned_);
  for (std::vector<double>* w : {&X, &u, &v, &a}) w->resize(3 * n);
  volume.resize(n);
  density.resize(n);
  mass.resize(n);
  material.resize(n);
  body.resize(n);
  id.resize(n);
  owned_ = -1;
}

void ParticleSet::drop_ghosts_from(int first) {
  MF_ASSERT(first >= owned_count() && first <= size());
  if (first == owned_count()) return drop_ghosts();
  const std::size_t n = static_cast<std::size_t>(first);
  for_each_array([n](auto& w, int per) { w.resize(per * n); });
}

} // namespace mf::particles
