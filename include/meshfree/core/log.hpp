#pragma once
// Progress messages on stdout, printed by MPI rank 0 only.
#include "meshfree/core/error.hpp"
#include <iostream>
#include <string>

namespace mf::log {

/// Rank of this process; set once by the solver context, 0 in serial tools and tests.
int& rank();
/// When false, info() prints nothing (tests keep their output short).
bool& verbose();

template <class... Args> void info(const Args&... args) {
  if (rank() == 0 && verbose()) std::cout << "[meshfree] " << detail::concat(args...) << std::endl;
}

/// A duration for progress lines, to 3 significant digits: "8.42 s", "12.5 min", "2.03 h".
std::string duration(double seconds);

/// "elapsed 8.42 s, about 25.3 s left": the time left estimated from the share done so far.
std::string eta(double elapsed_seconds, double fraction_done);

template <class... Args> void warn(const Args&... args) {
  if (rank() == 0) std::cerr << "[meshfree] warning: " << detail::concat(args...) << std::endl;
}

} // namespace mf::log
