#include "meshfree/pd/particle_order.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace mf::pd {

namespace {

/// The 21 low bits of v spread to every third bit (the "magic numbers" bit interleave).
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

template <class T> void permute(std::vector<T>& v, const std::vector<int>& order, int width) {
  std::vector<T> out(v.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    for (int d = 0; d < width; ++d)
      out[width * k + d] = v[width * static_cast<std::size_t>(order[k]) + d];
  v.swap(out);
}

} // namespace

std::uint64_t morton_key(const double* x, const double* lo, double cell) {
  std::uint64_t key = 0;
  for (int d = 0; d < 3; ++d) {
    const double c = std::floor((x[d] - lo[d]) / cell + 0.5);
    key |= spread(static_cast<std::uint64_t>(std::max(0.0, c))) << d;
  }
  return key;
}

std::vector<int> order_along_curve(particles::ParticleSet& p, double spacing) {
  MF_REQUIRE(p.owned_count() == p.size(), "order_along_curve: the set has ghost particles");
  const int n = p.size();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (n == 0) return order;
  double lo[3] = {p.X[0], p.X[1], p.X[2]};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p.X[3 * i + d]);
  std::vector<std::uint64_t> key(n);
  for (int i = 0; i < n; ++i) key[i] = morton_key(&p.X[3 * i], lo, spacing);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  p.for_each_field(
      [&order](const particles::FieldInfo& f, auto& a) { permute(a, order, f.components); });
  std::iota(p.id.begin(), p.id.end(), 0L);
  return order;
}

} // namespace mf::pd
