#include "meshfree/core/log.hpp"
#include "meshfree/core/timer.hpp"

namespace mf {

int& log::rank() {
  static int r = 0;
  return r;
}

bool& log::verbose() {
  static bool v = true;
  return v;
}

void PhaseTimer::add(const std::string& name, double seconds) {
  for (auto& [n, t] : phases_)
    if (n == name) {
      t += seconds;
      return;
    }
  phases_.emplace_back(name, seconds);
}

double PhaseTimer::total() const {
  double s = 0.0;
  for (const auto& p : phases_) s += p.second;
  return s;
}

} // namespace mf
