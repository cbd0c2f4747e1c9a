#include "meshfree/implicit/residual_terms.hpp"
#include <cmath>
#include <limits>

namespace mf::implicit {

void finish_residual(double* r, const std::vector<double>& penalty,
                     const std::vector<std::vector<double>>& loads,
                     const std::vector<double>& factors, const std::vector<char>& in_scale,
                     solvers::ResidualSums& sums) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double internal = 0.0, external = 0.0, floor = 0.0;
  for (std::size_t i = 0; i < penalty.size(); ++i) {
    double applied = 0.0, load = 0.0;
    for (std::size_t c = 0; c < loads.size(); ++c) {
      applied += factors[c] * loads[c][i];
      if (in_scale[c]) load += factors[c] * loads[c][i];
    }
    internal += r[i] * r[i];
    external += load * load;
    const double terms = std::abs(r[i]) + std::abs(penalty[i]) + std::abs(applied);
    floor += eps * terms * eps * terms;
    r[i] += penalty[i];
    r[i] -= applied;
  }
  sums.scale_squared = internal + external;
  sums.floor_squared = floor;
}

} // namespace mf::implicit
