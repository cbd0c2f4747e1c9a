#pragma once
// A barrier for the threads of one OpenMP parallel region that waits by spinning. OpenMP's own
// barrier puts a waiting thread to sleep at once under the passive wait policy the program runs
// with (src/app/main.cpp), and on a virtual machine whose idle cores halt, waking a sleeping
// thread costs tens of microseconds (README, peridynamics: the bond loop's cost), as much as the
// short phases of a step that the barrier separates. A thread that has spun for about a
// millisecond (another job on its core, a long serial phase) yields its core between tries.
#include <atomic>
#include <omp.h>
#include <thread>

namespace mf::pd {

class SpinBarrier {
public:
  /// Called by every thread of the enclosing region; returns when all have called it. Writes
  /// made before it by any thread are seen after it by every thread.
  void wait() {
    const int threads = omp_get_num_threads();
    if (threads == 1) return;
    const unsigned generation = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) == threads - 1) {
      arrived_.store(0, std::memory_order_relaxed);
      generation_.fetch_add(1, std::memory_order_release);
      return;
    }
    for (long spins = 0; generation_.load(std::memory_order_acquire) == generation; ++spins)
      if (spins < kSpins)
        pause();
      else
        std::this_thread::yield();
  }

private:
  static constexpr long kSpins = 1L << 15;
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  std::atomic<int> arrived_{0};
  std::atomic<unsigned> generation_{0};
};

} // namespace mf::pd
