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

class PhaseTimer {
public:
  /// Adds the seconds elapsed since `start` to phase `name`.
  void add(const std::string& name, double seconds);
  const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }
  double total() const;

  /// Times the enclosing scope into one phase.
  class Scope {
  public:
    Scope(PhaseTimer& timer, std::string name)
        : timer_(timer), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}
    ~Scope() { timer_.add(name_, seconds_since(start_)); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    PhaseTimer& timer_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
  };

private:
  std::vector<std::pair<std::string, double>> phases_;
};

} // namespace mf
