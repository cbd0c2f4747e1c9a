#pragma once
// The discrete system a load schedule drives (implicit/load_stepping), plane or 3D: the load
// factors of the next increment, and the commit of the material history once it has converged.
#include <vector>

namespace mf::implicit {

class IncrementalSystem {
public:
  virtual ~IncrementalSystem() = default;
  /// Load factors per boundary condition, then the body force.
  virtual void set_factors(const std::vector<double>& f) = 0;
  virtual void commit() = 0;
};

} // namespace mf::implicit
