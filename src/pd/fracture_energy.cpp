#include "meshfree/pd/fracture_energy.hpp"
#include <cmath>

namespace mf::pd {

double FractureEnergy::broken(const Model& m, const BondState& s,
                              const std::vector<unsigned char>& before,
                              const std::vector<double>& y) {
  const int owned = m.particles.owned_count();
  const bool plastic = !s.plastic.empty();
  // Per owned particle: the energy density and force density of its bonds that broke now.
  std::vector<double> w(owned, 0.0), f(3 * static_cast<std::size_t>(owned), 0.0);
  std::vector<unsigned char> any(owned, 0);
  // Serial: called only in evaluations that broke bonds, and it visits each bond once per end.
  for_each_directed_bond(m, [&](int i, int j, long k, double weight, const BondClass& c) {
    if (!before[k] || s.intact[k]) return;
    any[i] = 1;
    const double d[3] = {y[3 * j] - y[3 * i], y[3 * j + 1] - y[3 * i + 1],
                         y[3 * j + 2] - y[3 * i + 2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double stretch = (r - c.length) / c.length;
    const materials::BondLaw& law = m.laws[c.law];
    double sp = plastic ? s.plastic[k] : 0.0;
    // The force bond_forces applied (the plastic stretch it left is already in s.plastic).
    const double scale = r > 0.0 ? materials::bond_force(law, stretch, sp) * weight / r : 0.0;
    for (int e = 0; e < 3; ++e) f[3 * i + e] += scale * d[e];
    w[i] += 0.5 * materials::bond_energy(law, stretch, sp, c.length) * weight;
  });
  particle_.clear();
  force_.clear();
  double energy = 0.0;
  for (int i = 0; i < owned; ++i) {
    if (!any[i]) continue;
    const double V = m.particles.volume[i];
    energy += w[i] * V;
    particle_.push_back(i);
    for (int e = 0; e < 3; ++e) force_.push_back(V * f[3 * i + e]);
  }
  return energy;
}

double FractureEnergy::work_over_step(const std::vector<double>& du) {
  double w = 0.0;
  for (std::size_t e = 0; e < particle_.size(); ++e)
    for (int c = 0; c < 3; ++c) w += 0.5 * force_[3 * e + c] * du[3 * particle_[e] + c];
  particle_.clear();
  force_.clear();
  return w;
}

} // namespace mf::pd
