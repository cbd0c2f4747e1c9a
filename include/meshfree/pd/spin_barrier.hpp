#pragma once
// A barrier for the threads of one OpenMP parallel region that spins for a short while before it
// sleeps. OpenMP's own barrier puts a waiting thread to sleep at once under the passive wait
// policy the program runs with (src/app/main.cpp), and on a virtual machine whose idle cores
// halt, waking a sleeping thread costs tens of microseconds (README, peridynamics: the bond
// loop's cost), as much as the short phases of a step that the barrier separates; the threads of
// a quiet machine reach it within microseconds of each other. A thread that has spun its budget
// sleeps (a futex on Linux, else it yields), so that on a machine shared with other jobs a thread
// waiting for a descheduled one gives its core away; the budget (per thread, kept from one
// barrier to the next) halves when a spin ends in sleep and grows by half when it does not, as
// the halt polling of a virtual machine's idle loop adapts (Linux cpuidle-haltpoll), so that
// spinning costs little where it does not pay.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <omp.h>
#include <thread>
#if defined(__linux__)
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace mf::pd {

class SpinBarrier {
public:
  /// Called by every thread of the enclosing region; returns when all have called it. Writes
  /// made before it by any thread are seen after it by every thread.
  void wait() {
    const int threads = omp_get_num_threads();
    if (threads == 1) return;
    const unsigned generation = generation_.load();
    if (arrived_.fetch_add(1) == threads - 1) {
      arrived_.store(0);
      generation_.fetch_add(1);
      if (sleepers_.load() > 0) wake_all();
      return;
    }
    double& budget = spin_budget();
    if (spin(generation, budget)) {
      budget = std::min(kMaxSpin, 1.5 * budget);
      return;
    }
    budget = std::max(kMinSpin, 0.5 * budget);
    sleepers_.fetch_add(1);
    while (generation_.load() == generation) sleep(generation);
    sleepers_.fetch_sub(1);
  }

private:
  static constexpr double kMinSpin = 2e-6, kMaxSpin = 2e-4; // seconds

  static double& spin_budget() {
    thread_local double budget = 5e-5;
    return budget;
  }

  /// Spins until the generation moves on (true) or `seconds` have passed (false).
  bool spin(unsigned generation, double seconds) const {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(seconds));
    for (int k = 1;; ++k) {
      if (generation_.load(std::memory_order_acquire) != generation) return true;
      pause();
      if (k % 64 == 0 && Clock::now() > end) return false;
    }
  }
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  /// Sleeps while the generation is still `generation` (or returns at once).
  void sleep(unsigned generation) {
#if defined(__linux__)
    syscall(SYS_futex, reinterpret_cast<unsigned*>(&generation_), FUTEX_WAIT_PRIVATE, generation,
            nullptr, nullptr, 0);
#else
    (void)generation;
    std::this_thread::yield();
#endif
  }
  void wake_all() {
#if defined(__linux__)
    syscall(SYS_futex, reinterpret_cast<unsigned*>(&generation_), FUTEX_WAKE_PRIVATE, INT_MAX,
            nullptr, nullptr, 0);
#endif
  }
  // Sequentially consistent throughout: a thread going to sleep counts itself in `sleepers_`
  // before it reads the generation, the last thread moves the generation on before it reads
  // `sleepers_`, so one of the two sees the other's write and no wake-up is lost.
  std::atomic<int> arrived_{0};
  std::atomic<unsigned> generation_{0};
  std::atomic<int> sleepers_{0};
};

static_assert(sizeof(std::atomic<unsigned>) == sizeof(unsigned),
              "the futex waits on the generation's own word");

} // namespace mf::pd
