// Phase timers: a staged run's summary gathers the phases of its stages under their names, wall
// and kernel seconds both (kernel_time_s was all zeros when only the wall seconds were carried).
#include "meshfree/core/timer.hpp"
#include <catch2/catch.hpp>

using namespace mf;

TEST_CASE("a timer's phases are added to another under a prefix, kernel seconds included",
          "[timer]") {
  PhaseTimer stage, run;
  stage.add("newton", 2.0, 0.5);
  stage.add("output", 1.0, 0.25);
  run.add("preload.newton", 1.0, 0.125);
  run.add_all(stage, "preload.");
  REQUIRE(run.phases().size() == 2);
  CHECK(run.phases()[0].first == "preload.newton");
  CHECK(run.phases()[0].second == 3.0);
  CHECK(run.kernel_phases()[0].second == 0.625);
  CHECK(run.phases()[1].first == "preload.output");
  CHECK(run.kernel_phases()[1].second == 0.25);
  CHECK(run.total() == 4.0);
}
