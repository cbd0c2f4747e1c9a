#include "meshfree/pd/fracture_energy.hpp"
#include <cmath>

namespace mf::pd {

double FractureEnergy::broken(const Model& m, const BondState& s,
                              const std::vector<unsigned char>& before,
                              const std::vector<double>& y) {
  const Bonds& b = m.bonds;
  const int n = m.particles.size();
  const bool plastic = !s.plastic.empty();
  particle_.clear();
  force_.clear();
  double energy = 0.0;
  // Serial: called only in evaluations that broke bonds, and it visits each bond once.
  for (int i = 0; i < n; ++i) {
    double w_i = 0.0, f[3] = {0.0, 0.0, 0.0};
    bool any = false;
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!before[k] || s.intact[k]) continue;
      any = true;
      const int j = b.partner[k];
      const double d[3] = {y[3 * j] - y[3 * i], y[3 * j + 1] - y[3 * i + 1],
                           y[3 * j + 2] - y[3 * i + 2]};
      const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double L = b.length[k];
      const double stretch = (r - L) / L;
      const materials::BondLaw& law = m.laws[b.law[k]];
      double sp = plastic ? s.plastic[k] : 0.0;
      // The force bond_forces applied (the plastic stretch it left is already in s.plastic).
      const double scale =
          r > 0.0 ? materials::bond_force(law, stretch, sp) * b.weight[k] / r : 0.0;
      for (int c = 0; c < 3; ++c) f[c] += scale * d[c];
      w_i += 0.5 * materials::bond_energy(law, stretch, sp, L) * b.weight[k];
    }
    if (!any) continue;
    const double V = m.particles.volume[i];
    energy += w_i * V;
    particle_.push_back(i);
    for (int c = 0; c < 3; ++c) force_.push_back(V * f[c]);
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
