#pragma once
// Progress lines of a long phase counted in units of work (integration points assembled, the
// decades of a residual reduced): one at every tenth of the work, one at least every 10 s of
// wall time between them, and a final 100% line, each with the time elapsed and the time left
// to 3 significant digits (log::eta).
#include <atomic>
#include <functional>
#include <string>

namespace mf::log {

/// Systems from this many unknowns up report the progress of their assembly and solve at every
/// tenth (a 10^6-DOF plate, 999,698 unknowns, takes tens of seconds in each).
inline constexpr double kProgressUnknowns = 5e5;

class PhaseProgress {
public:
  using Seconds = std::function<double()>;               // wall time since the phase began
  using Print = std::function<void(const std::string&)>; // one line, without its newline
  /// A phase `label` of `total` units; prints nothing unless `enabled`, and with `tenths`
  /// false only the 10 s lines (no line for the tenths nor the 100% line: phases that are
  /// short as a rule and would otherwise print ten lines each). By default the clock is the
  /// steady clock from construction and lines go to log::info.
  PhaseProgress(std::string label, double total, bool enabled, Seconds seconds = {},
                Print print = {}, bool tenths = true);
  /// `done` units are finished (not decreasing; values beyond total count as total); `detail`,
  /// if a line is printed, follows its percentage (", iteration 40").
  void update(double done, const std::string& detail = "");
  /// One unit done, from any thread of a parallel loop: counted at once (an atomic add), and
  /// passed to `update` by thread 0 once every 4096 units, so that a loop over millions of
  /// integration points reads no clock and calls nothing per point. Nothing if disabled.
  void count_one(int thread);
  /// The 100% line, once; nothing if disabled.
  void finish();

private:
  void report(double fraction, const std::string& detail);
  std::string label_;
  double total_;
  bool enabled_, tenths_, finished_ = false;
  Seconds seconds_;
  Print print_;
  int next_tenth_ = 1;
  std::atomic<long> counted_{0};
  long passed_on_ = 0; // the count last given to update by count_one (thread 0 only)
  double last_line_ = 0.0; // the time of the last line
};

/// "42%": the share of `fraction` in whole percent, floored (so 100% means done).
std::string percent(double fraction);

} // namespace mf::log
