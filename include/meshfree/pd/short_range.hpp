#pragma once
// Short-range repulsion between particles that come too close, bonded or not (fragments that
// meet again, a body pressed on itself): the contact force of LAMMPS pair peri/pmb
// (src/PERI/pair_peri_pmb.cpp, PairPeriPMB::compute, "short-range contact forces"; the constant
// 15 from the EMU theory manual, Silling 2005, p. 18). For particles i, j at distance r below
//   d_ij = min(0.9 |X_i - X_j|, 1.35 lc)      (X: reference positions, lc: the lattice spacing)
// i gets the force per unit volume 15 c_ij V_j (d_ij - r) / delta along (y_i - y_j) / r, j the
// same with V_i (LAMMPS applies V_j to both, the same on the uniform lattices it is meant for;
// with V_i for j the pair's forces V_i f_i + V_j f_j cancel). The pair's potential energy is
// 15 c_ij V_i V_j (d_ij - r)^2 / (2 delta).
// Pairs come from a cell list of the current positions out to 1.35 lc plus a skin, rebuilt when
// a particle has moved more than half the skin since the last build (LAMMPS's neighbour check).
#include "meshfree/neighbors/pair_list.hpp"
#include "meshfree/pd/model.hpp"
#include <vector>

namespace mf::pd {

class ShortRangeContact {
public:
  /// For the body `m` (its spacing is lc, its horizon delta); `skin` in units of the spacing.
  explicit ShortRangeContact(const Model& m, double skin = 1.0);

  /// Adds the contact force densities at positions y (3 per particle) to `force`; returns the
  /// contact potential energy.
  double add_forces(const Model& m, const std::vector<double>& y, std::vector<double>& force);

  long rebuilds() const { return rebuilds_; }

  /// The pair list and where the particles were when it was built (a checkpoint keeps them).
  /// The partners vary in number as the run goes; the rows are the particles.
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("offset", pairs_.offset), visit.resizing()("partner", pairs_.partner);
    visit("y_built", y_built_), visit("rebuilds", rebuilds_);
  }
  /// The list names only the particles it was built for.
  bool consistent() const {
    return pairs_.consistent() && y_built_.size() == 3 * static_cast<std::size_t>(pairs_.rows());
  }

private:
  void rebuild(const std::vector<double>& y);

  double reach_ = 0.0, skin_ = 0.0;
  neighbors::PairList pairs_;
  std::vector<double> y_built_;
  long rebuilds_ = 0;
};

} // namespace mf::pd
