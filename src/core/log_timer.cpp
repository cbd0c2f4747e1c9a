#include "meshfree/core/log.hpp"
#include "meshfree/core/timer.hpp"
#include <cmath>
#include <cstdio>
#include <sys/resource.h>

namespace mf {

int& log::rank() {
  static int r = 0;
  return r;
}

bool& log::verbose() {
  static bool v = true;
  return v;
}

std::string log::duration(double seconds) {
  double v = seconds;
  const char* unit = "s";
  if (seconds >= 3600.0)
    v = seconds / 3600.0, unit = "h";
  else if (seconds >= 120.0)
    v = seconds / 60.0, unit = "min";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %s", v, unit);
  return text;
}

std::string log::eta(double elapsed_seconds, double fraction_done) {
  std::string s = "elapsed " + duration(elapsed_seconds);
  if (fraction_done > 0.0 && fraction_done < 1.0 && std::isfinite(elapsed_seconds))
    s += ", about " + duration(elapsed_seconds * (1.0 - fraction_done) / fraction_done) + " left";
  return s;
}

double kernel_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_stime.tv_usec);
}

void PhaseTimer::add(const std::string& name, double seconds, double kernel) {
  for (std::size_t k = 0; k < phases_.size(); ++k)
    if (phases_[k].first == name) {
      phases_[k].second += seconds;
      kernel_[k].second += kernel;
      return;
    }
  phases_.emplace_back(name, seconds);
  kernel_.emplace_back(name, kernel);
}

void PhaseTimer::add_all(const PhaseTimer& other, const std::string& prefix) {
  for (std::size_t k = 0; k < other.phases_.size(); ++k)
    add(prefix + other.phases_[k].first, other.phases_[k].second, other.kernel_[k].second);
}

double PhaseTimer::total() const {
  double s = 0.0;
  for (const auto& p : phases_) s += p.second;
  return s;
}

} // namespace mf
