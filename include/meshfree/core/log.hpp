#pragma once
// Progress messages on stdout, printed by MPI rank 0 only.
#include "meshfree/core/error.hpp"
#include <iostream>

namespace mf::log {

/// Rank of this process; set once by the solver context, 0 in serial tools and tests.
int& rank();
/// When false, info() prints nothing (tests keep their output short).
bool& verbose();

template <class... Args> void info(const Args&... args) {
  if (rank() == 0 && verbose()) std::cout << "[meshfree] " << detail::concat(args...) << std::endl;
}

template <class... Args> void warn(const Args&... args) {
  if (rank() == 0) std::cerr << "[meshfree] warning: " << detail::concat(args...) << std::endl;
}

} // namespace mf::log
