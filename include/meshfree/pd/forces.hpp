#pragma once
// The bond forces of a peridynamic body: the hot loop. For particle i at current position y_i,
//   F_i = sum_j mu_ij f(s_ij) e_ij w_ij   (force per unit volume; w_ij = V_j times corrections),
// with f from the bond law (materials::bond_force), s the bond stretch and e the current bond
// direction (Silling & Askari 2005, eq. 3 discretised). The loop is chosen once per call by the
// bond layout (BondLayout: each pair once with Newton's third law and per-thread buffers, or full
// rows summed in global-id order) and by the kind of law (elastic or micro-plastic, with or
// without the LAMMPS alpha rule, with or without energies) and the instruction set
// (pd/bond_rows.hpp: scalar, AVX2 or AVX-512 rows, the same numbers bit for bit): no per-bond
// law lookup, no virtual call; the per-bond constants come from the bond's class.
#include "meshfree/pd/bond_rows.hpp"
#include "meshfree/pd/model.hpp"
#include <vector>

namespace mf::pd {

struct ForceReport {
  long broken = 0; // bonds broken in this evaluation: directed bonds (a pair of owned particles
                   // counts 2, an owned-ghost pair 1)
  double strain_energy = 0.0; // sum_i V_i W_i, W_i = 1/2 sum_j w(s_ij) w_ij, if asked for
};

/// Fills `force` (3 per particle) at positions `y` (3 per particle). A bond whose stretch exceeds
/// its critical stretch is broken after its force has counted in this evaluation (the order of
/// LAMMPS peri/pmb); with the LAMMPS alpha rule the critical stretch is min(s0_i, s0_j) from the
/// previous evaluation, and s0 is renewed. `energy_density` (optional, one per particle) gets W_i.
ForceReport bond_forces(const Model& m, BondState& s, const std::vector<double>& y,
                        std::vector<double>& force, bool with_energy = false,
                        std::vector<double>* energy_density = nullptr);

/// bond_forces in its parts, for a caller that runs them in a parallel region of its own (one
/// region for a whole step, pd::advance). One thread constructs it (the outputs zeroed); then
/// every thread of the region calls rows(), waits for all (pd::SpinBarrier), calls finish() and
/// waits for all; then one thread takes report(). bond_forces is the same in a region of its own.
class BondForcePass {
public:
  BondForcePass(const Model& m, BondState& s, const std::vector<double>& y,
                std::vector<double>& force, bool with_energy,
                std::vector<double>* energy_density = nullptr);
  /// The calling thread's rows (half layout: a range with an equal share of the bonds; full
  /// layout: chunks of rows handed out in turn).
  void rows();
  /// The calling thread's share of the points: the other threads' buffers added in thread order,
  /// the LAMMPS rule's s0 kept where no intact bond gave one.
  void finish();
  /// Bonds broken and strain energy (summed in thread order); commits s0.
  ForceReport report();

private:
  BondState& s_;
  rows::Arrays a_;
  rows::Terms terms_;
  SimdTarget target_;
  bool half_;
  int points_;
  double* force_;
  double* density_;
  double* s0_trial_;
  std::vector<rows::Output> outputs_; // per thread (half layout)
  std::vector<long> broken_;          // per thread
  std::vector<double> energy_;        // per thread (half layout)
};

} // namespace mf::pd
