#pragma once
// A transmitting (non-reflecting) boundary on a surface layer of particles, a boundary condition
// of an SPH run (sph/condition.hpp): Lysmer & Kuhlemeyer (1969) dashpots, a traction
// -rho c_p (v.n) n - rho c_s (v - (v.n) n) on each particle's face area, which absorbs plane
// waves arriving along the normal. A body cut out of a stressed medium (soil under its own
// weight) also needs the traction sigma0 . n that the medium beyond the boundary exerted on it,
// else the boundary gives way under the initial stress (the "free-field" or reaction forces of
// viscous boundaries; Lysmer & Kuhlemeyer 1969, and e.g. Kontoe, Zdravkovic & Potts 2009):
// static_force holds it, 3 per particle, constant (empty: none; sph::hold_stress sets it).
#include "meshfree/sph/condition.hpp"
#include <string>
#include <vector>

namespace mf::sph {

struct TransmittingBoundary final : Condition {
  std::string name;
  std::vector<int> particles;
  std::vector<double> area, normal_impedance, shear_impedance; // A, rho c_p, rho c_s per particle
  double normal[3] = {0.0, 0.0, 0.0};                          // unit, outward
  std::vector<double> static_force;                            // 3 per particle, or empty

  /// The dashpot force of particle k of the boundary at velocity v, plus its static force.
  void force_on(std::size_t k, const double* v, double f[3]) const;

  std::unique_ptr<Condition> clone() const override;
  const std::string& label() const override { return name; }
  int order() const override { return 2; }
  void add_accelerations(const Hydro& s, double t, std::vector<double>& dv) const override;
  void append_forces(const Hydro& s, double t, std::vector<int>& who,
                     std::vector<double>& force) const override;
  std::unique_ptr<Condition> owned_part(const particles::ParticleSet& P) const override;
  double largest_held_force() const override;
};

} // namespace mf::sph
