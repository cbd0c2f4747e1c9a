#include "meshfree/pd/fracture_energy.hpp"
#include "meshfree/pd/state_based.hpp"
#include <cmath>

namespace mf::pd {

double FractureEnergy::broken(const Model& m, const BondState& s,
                              const std::vector<unsigned char>& before,
                              const std::vector<double>& y) {
  if (m.state_based()) return broken_states(m, s, before, y);
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

double FractureEnergy::broken_states(const Model& m, const BondState& s,
                                     const std::vector<unsigned char>& before,
                                     const std::vector<double>& y) {
  // A state-based body's energy is not a sum over bonds: the break changes the dilatation of
  // both ends and so the force of every bond of theirs and their partners'. What it took is the
  // body's energy with the bonds before less that after, at the same y, and its force the
  // difference of the two force fields.
  std::vector<double> f_before, f_after, w_before, w_after;
  state_forces_kept(m, before, s.plastic, y, f_before, w_before);
  state_forces_kept(m, s.intact, s.plastic, y, f_after, w_after);
  particle_.clear();
  force_.clear();
  double energy = 0.0;
  for (int i = 0; i < m.particles.owned_count(); ++i) {
    const double V = m.particles.volume[i];
    energy += V * (w_before[i] - w_after[i]);
    const double d[3] = {f_before[3 * i] - f_after[3 * i], f_before[3 * i + 1] - f_after[3 * i + 1],
                         f_before[3 * i + 2] - f_after[3 * i + 2]};
    if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) continue;
    particle_.push_back(i);
    for (int e = 0; e < 3; ++e) force_.push_back(V * d[e]);
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
