// Progress lines of long phases (assembly and solve of large implicit systems): one per tenth of
// the work, one at least every 10 s between them, a final 100% line, times to 3 significant
// digits.
#include "meshfree/core/progress.hpp"
#include <catch2/catch.hpp>
#include <string>
#include <vector>

using mf::log::PhaseProgress;

namespace {

/// A phase of `total` units on a clock the test moves, its lines collected.
struct Recorded {
  double now = 0.0;
  std::vector<std::string> lines;
  PhaseProgress make(double total, bool enabled = true, bool tenths = true) {
    return PhaseProgress(
        "assembly", total, enabled, [this] { return now; },
        [this](const std::string& line) { lines.push_back(line); }, tenths);
  }
};

} // namespace

TEST_CASE("a fast phase prints one line per tenth and the 100% line", "[progress]") {
  Recorded r;
  PhaseProgress p = r.make(1000);
  for (int k = 1; k <= 1000; ++k) {
    r.now = 0.0123456 * k; // 12.3456 s in all: no 10 s gap between two tenths
    p.update(k);
  }
  p.finish(); // already printed by the last update: not twice
  REQUIRE(r.lines.size() == 10);
  CHECK(r.lines[0] == "assembly: 10%, elapsed 1.23 s, about 11.1 s left");
  CHECK(r.lines[4] == "assembly: 50%, elapsed 6.17 s, about 6.17 s left");
  CHECK(r.lines[8] == "assembly: 90%, elapsed 11.1 s, about 1.23 s left");
  CHECK(r.lines[9] == "assembly: 100%, elapsed 12.3 s");
}

TEST_CASE("a slow phase prints at least every 10 s between its tenths", "[progress]") {
  Recorded r;
  PhaseProgress p = r.make(200);
  for (int k = 1; k < 200; ++k) {
    r.now = 1.5 * k; // 300 s in all: 30 s per tenth
    p.update(k, ", step " + std::to_string(k));
  }
  r.now = 300.0;
  p.finish();
  // Every 10 s (7 updates of 1.5 s) and at every tenth: lines at k = 7, 14, 20 (the tenth),
  // 27, ...
  REQUIRE(r.lines.size() >= 30);
  CHECK(r.lines[0] == "assembly: 3%, step 7, elapsed 10.5 s, about 4.83 min left");
  CHECK(r.lines[1] == "assembly: 7%, step 14, elapsed 21 s, about 4.65 min left");
  CHECK(r.lines[2] == "assembly: 10%, step 20, elapsed 30 s, about 4.5 min left");
  CHECK(r.lines.back() == "assembly: 100%, elapsed 5 min");
}

TEST_CASE("work that jumps over several tenths prints one line", "[progress]") {
  Recorded r;
  PhaseProgress p = r.make(10);
  r.now = 2.0;
  p.update(3.5);
  r.now = 3.0;
  p.update(3.9); // no new tenth, 1 s later: nothing
  r.now = 4.0;
  p.update(12.0); // beyond the total: done
  REQUIRE(r.lines.size() == 2);
  CHECK(r.lines[0] == "assembly: 35%, elapsed 2 s, about 3.71 s left");
  CHECK(r.lines[1] == "assembly: 100%, elapsed 4 s");
}

TEST_CASE("a disabled phase prints nothing, one without tenths only its 10 s lines", "[progress]") {
  Recorded off;
  PhaseProgress p = off.make(10, false);
  off.now = 100.0;
  p.update(5);
  p.finish();
  CHECK(off.lines.empty());

  Recorded quiet;
  PhaseProgress q = quiet.make(10, true, false);
  quiet.now = 1.0;
  q.update(5); // a tenth, but no 10 s yet
  quiet.now = 12.0;
  q.update(6);
  q.finish();
  REQUIRE(quiet.lines.size() == 1);
  CHECK(quiet.lines[0] == "assembly: 60%, elapsed 12 s, about 8 s left");
}

TEST_CASE("percentages are floored, so 100% means done", "[progress]") {
  CHECK(mf::log::percent(0.999) == "99%");
  CHECK(mf::log::percent(1.0) == "100%");
  CHECK(mf::log::percent(-0.5) == "0%");
  CHECK(mf::log::percent(0.1) == "10%");
}

TEST_CASE("units counted from a parallel loop reach the lines through thread 0", "[progress]") {
  Recorded r;
  PhaseProgress p = r.make(10000);
  for (int k = 1; k <= 4095; ++k) p.count_one(k % 2); // two threads' units, none passed on yet
  CHECK(r.lines.empty());
  p.count_one(1); // the 4096th unit, counted on thread 1: thread 0 passes counts on
  CHECK(r.lines.empty());
  p.count_one(0); // 4097 units: 40%
  REQUIRE(r.lines.size() == 1);
  CHECK(r.lines[0].rfind("assembly: 40%", 0) == 0);
  for (int k = 0; k < 5903; ++k) p.count_one(0); // every unit done: the last lines and 100%
  p.finish();
  CHECK(r.lines.back() == "assembly: 100%, elapsed 0 s");
  PhaseProgress off = r.make(10, false);
  for (int k = 0; k < 5000; ++k) off.count_one(0);
  CHECK(r.lines.size() == 3); // 40%, 81%, 100%; nothing from the disabled phase
}
