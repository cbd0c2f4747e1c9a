#pragma once
// Constant forces on a set of particles (a held traction, a preload kept on, the balance of a
// body held at rest), a boundary condition of an SPH run (sph/condition.hpp). sph/held_loads.hpp
// builds one from a traction, sph/support_balance.hpp one that balances a body at rest.
#include "meshfree/sph/condition.hpp"
#include <string>
#include <vector>

namespace mf::sph {

/// Particle particles[k] takes force[3k..3k+2] at all times; fixed particles take none.
struct SurfaceForce final : Condition {
  std::string name;
  std::vector<int> particles;
  std::vector<double> force; // 3 per particle

  std::unique_ptr<Condition> clone() const override;
  const std::string& label() const override { return name; }
  int order() const override { return 1; }
  void add_accelerations(const Hydro& s, double t, std::vector<double>& dv) const override;
  void append_forces(const Hydro& s, double t, std::vector<int>& who,
                     std::vector<double>& force) const override;
  std::unique_ptr<Condition> owned_part(const particles::ParticleSet& P) const override;
  double largest_held_force() const override;
};

} // namespace mf::sph
