#include "meshfree/core/progress.hpp"
#include "meshfree/core/log.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>

namespace mf::log {

namespace {

/// The longest wall time between two progress lines.
constexpr double kLineSeconds = 10.0;

} // namespace

std::string percent(double fraction) {
  const double f = std::clamp(fraction, 0.0, 1.0);
  return std::to_string(static_cast<int>(std::floor(100.0 * f + 1e-9))) + "%";
}

PhaseProgress::PhaseProgress(std::string label, double total, bool enabled, Seconds seconds,
                             Print print, bool tenths)
    : label_(std::move(label)), total_(total), enabled_(enabled), tenths_(tenths),
      seconds_(std::move(seconds)), print_(std::move(print)) {
  if (!seconds_) {
    const auto start = std::chrono::steady_clock::now();
    seconds_ = [start] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
  }
  if (!print_) print_ = [](const std::string& line) { info(line); };
}

void PhaseProgress::update(double done, const std::string& detail) {
  if (!enabled_ || finished_ || !(total_ > 0.0)) return;
  const double fraction = std::clamp(done / total_, 0.0, 1.0);
  if (fraction >= 1.0) return finish();
  const bool tenth = tenths_ && fraction >= 0.1 * next_tenth_;
  if (!tenth && seconds_() - last_line_ < kLineSeconds) return;
  while (next_tenth_ <= 10 && fraction >= 0.1 * next_tenth_) ++next_tenth_;
  report(fraction, detail);
}

void PhaseProgress::count_one(int thread) {
  if (!enabled_) return;
  const long n = ++counted_;
  if (thread != 0 || n - passed_on_ < 4096) return;
  passed_on_ = n;
  update(static_cast<double>(n));
}

void PhaseProgress::finish() {
  if (!enabled_ || !tenths_ || finished_) return;
  finished_ = true;
  report(1.0, "");
}

void PhaseProgress::report(double fraction, const std::string& detail) {
  last_line_ = seconds_();
  print_(label_ + ": " + percent(fraction) + detail + ", " + eta(last_line_, fraction));
}

} // namespace mf::log
