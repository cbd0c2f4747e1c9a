#pragma once
// The material update of every Gauss point of a body, plane or solid, in parallel: a point whose
// update throws (a strain or stress that is not finite, a return that did not converge) ends it,
// the first such point by index named with its position, whatever the thread count.
#include "meshfree/core/error.hpp"
#include "meshfree/implicit/point_coupling.hpp"
#include <exception>
#include <string>

namespace mf::implicit {

/// Calls update(k) for k in [0, n); on failure throws "material update failed at the Gauss point
/// (x, y[, z]): <reason>", with position(k) the point's coordinates as an Eigen vector.
template <class Update, class Position>
void update_every_point(int n, const Update& update, const Position& position) {
  int failed = n;
  std::string message;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) {
    try {
      update(k);
    } catch (const std::exception& e) {
#pragma omp critical
      if (k < failed) failed = k, message = e.what();
    }
  }
  if (failed == n) return;
  fail("material update failed at the Gauss point (", point_text(position(failed)), "): ", message);
}

} // namespace mf::implicit
