#pragma once
// Wall-clock time per named phase, in the order the phases first ran.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace mf {

/// Seconds of wall-clock time since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CPU seconds the process has spent in the kernel so far, all threads together (getrusage).
double kernel_seconds();

class PhaseTimer {
public:
  /// Adds `seconds` of wall-clock time, `kernel` of them CPU seconds in the kernel, to `name`.
  void add(const std::string& name, double seconds, double kernel = 0.0);
  /// Adds every phase of `other`, wall and kernel seconds, as `prefix` + its name.
  void add_all(const PhaseTimer& other, const std::string& prefix);
  const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }
  /// Kernel CPU seconds per phase: for the most part paging in fresh memory, which costs several
  /// times more on some virtual machines and so explains time that grows faster than the work.
  const std::vector<std::pair<std::string, double>>& kernel_phases() const { return kernel_; }
  double total() const;

  /// Times the enclosing scope into one phase.
  class Scope {
  public:
    Scope(PhaseTimer& timer, std::string name)
        : timer_(timer), name_(std::move(name)), start_(std::chrono::steady_clock::now()),
          kernel_start_(kernel_seconds()) {}
    ~Scope() { timer_.add(name_, seconds_since(start_), kernel_seconds() - kernel_start_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    PhaseTimer& timer_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
    double kernel_start_;
  };

private:
  std::vector<std::pair<std::string, double>> phases_, kernel_;
};

} // namespace mf
