#include "meshfree/pd/forces.hpp"
#include <algorithm>
#include <cmath>

namespace mf::pd {

ForceReport bond_forces(const Model& m, BondState& s, const std::vector<double>& y,
                        std::vector<double>& force, bool with_energy,
                        std::vector<double>* energy_density) {
  const int n = m.particles.size();
  const Bonds& b = m.bonds;
  const materials::BondLaw* laws = m.laws.data();
  const bool plastic = !s.plastic.empty();
  const bool alpha = !s.s0.empty();
  force.assign(3 * static_cast<std::size_t>(n), 0.0);
  if (energy_density) energy_density->assign(n, 0.0);
  long broken = 0;
  double energy = 0.0;
#pragma omp parallel for schedule(dynamic, 512) reduction(+ : broken, energy)
  for (int i = 0; i < n; ++i) {
    const double xi = y[3 * i], yi = y[3 * i + 1], zi = y[3 * i + 2];
    double fx = 0.0, fy = 0.0, fz = 0.0, w_i = 0.0;
    double s0_next = 0.0; // LAMMPS rule: max over intact bonds of s00 - alpha s
    bool first = true;
    for (long k = b.offset[i]; k < b.offset[i + 1]; ++k) {
      if (!s.intact[k]) continue;
      const int j = b.partner[k];
      const double dx = y[3 * j] - xi, dy = y[3 * j + 1] - yi, dz = y[3 * j + 2] - zi;
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double L = b.length[k];
      const double stretch = (r - L) / L;
      const materials::BondLaw& law = laws[b.law[k]];
      double sp = plastic ? s.plastic[k] : 0.0;
      const double f = materials::bond_force(law, stretch, sp);
      if (plastic) s.plastic[k] = sp;
      const double scale = r > 0.0 ? f * b.weight[k] / r : 0.0;
      fx += scale * dx;
      fy += scale * dy;
      fz += scale * dz;
      if (with_energy) w_i += 0.5 * materials::bond_energy(law, stretch, sp, L) * b.weight[k];
      if (alpha) {
        const double candidate = law.critical_stretch - law.alpha * stretch;
        s0_next = first ? candidate : std::max(s0_next, candidate);
        first = false;
      }
      if (law.breaks()) {
        const double limit =
            alpha ? std::min(s.s0.committed[i], s.s0.committed[j]) : law.critical_stretch;
        if (stretch > limit) {
          s.intact[k] = 0;
          ++broken;
        }
      }
    }
    force[3 * i] = fx;
    force[3 * i + 1] = fy;
    force[3 * i + 2] = fz;
    // LAMMPS peri/pmb: the next step's s0_i follows the most compressed intact bond
    // (s00 - alpha s), so a compressed neighbourhood tolerates more stretch.
    if (alpha) s.s0.trial[i] = first ? s.s0.committed[i] : s0_next;
    if (with_energy) {
      energy += w_i * m.particles.volume[i];
      if (energy_density) (*energy_density)[i] = w_i;
    }
  }
  if (alpha) s.s0.commit();
  return {broken, energy};
}

} // namespace mf::pd
