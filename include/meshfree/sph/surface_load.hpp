#pragma once
// A pressure history on a surface layer of particles (an empirical blast load), a boundary
// condition of an SPH run (sph/condition.hpp).
#include "meshfree/loads/blast.hpp"
#include "meshfree/sph/condition.hpp"
#include <string>
#include <vector>

namespace mf::sph {

/// Particle k of the layer takes the force pulses[k](t) area[k] along `direction` (the inward
/// normal); fixed particles take none. A load of the event: a staged run's settle goes without it.
struct SurfaceLoad final : Condition {
  std::string name;
  std::vector<int> particles;
  std::vector<double> area;
  std::vector<loads::Friedlander> pulses;
  double direction[3] = {0.0, 0.0, 0.0};

  std::unique_ptr<Condition> clone() const override;
  const std::string& label() const override { return name; }
  int order() const override { return 0; }
  void add_accelerations(const Hydro& s, double t, std::vector<double>& dv) const override;
  void append_forces(const Hydro& s, double t, std::vector<int>& who,
                     std::vector<double>& force) const override;
  std::unique_ptr<Condition> owned_part(const particles::ParticleSet& P) const override;
  bool part_of_event() const override { return true; }
};

} // namespace mf::sph
