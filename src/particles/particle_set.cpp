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

int ParticleSet::add_ghost(int source) {
  if (owned_ < 0) owned_ = size();
  const auto copy3 = [source](std::vector<double>& w) {
    for (int d = 0; d < 3; ++d) w.push_back(w[3 * static_cast<std::size_t>(source) + d]);
  };
  copy3(X);
  copy3(u);
  copy3(v);
  copy3(a);
  volume.push_back(volume[source]);
  density.push_back(density[source]);
  mass.push_back(mass[source]);
  material.push_back(material[source]);
  body.push_back(body[source]);
  id.push_back(id[source]);
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

} // namespace mf::particles
