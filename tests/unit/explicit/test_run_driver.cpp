// The one end of every explicit run (explicit/run_driver.hpp): the history streamed to
// history.csv with the rows recorded before the loop, the checkpoints of the spec's policy and
// their counts, the loop's report handed to the run's finish, and a restart from the place's
// checkpoint going on as the run it came from.
#include "meshfree/explicit/run_driver.hpp"
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

using namespace mf;

namespace {

/// The spec keys the driver reads, as spec::PdSpec and spec::SphSpec hold them.
struct Spec {
  double end_time = 2.05;
  spec::SeriesOutputSpec output{0.25, 0.5, {}, {0.7, 0.0}};
};

/// One particle at unit speed, a history row {t, x} per recorded instant.
struct Walk {
  io::History history{{"time", "x"}};
  double t = 0.0, x = 0.0;
  long n = 0;
  std::vector<double> written;
  explicit_dynamics::LoopReport report;
  bool finished = false;
  double time() const { return t; }
  long step() const { return n; }
  bool time_step(double remaining, double& dt, std::string&) const {
    dt = std::min(0.1, remaining);
    return true;
  }
  void advance(double dt, bool) { t += dt, x += dt, ++n; }
  void track() {}
  int nonfinite() const { return -1; }
  Vec3 position(int) const { return Vec3::Zero(); }
  std::string advice() const { return ""; }
  void record() { history.append({t, x}); }
  void write_fields() { written.push_back(t); }
  std::string progress() const { return ""; }
  void save(io::Checkpoints&, const io::Saver& save) {
    save("t", t), save("x", x), save("n", n), save("written", written);
    history.for_each_state(save / "history");
  }
  void restore(const io::Loader& load) {
    load("t", t), load("x", x), load("n", n), load("written", written);
    history.for_each_state(load / "history");
  }
  void finish(const explicit_dynamics::LoopReport& loop) { report = loop, finished = true; }
};

std::vector<std::string> lines_of(const std::string& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

} // namespace

TEST_CASE("run_to_end streams the history, keeps the checkpoints and finishes the run",
          "[explicit][driver]") {
  const std::string dir = "test_run_driver";
  std::filesystem::remove_all(dir);
  const spec::ProblemSettings settings{{"time.end", "2.05"}};
  const Spec spec;
  Walk whole; // the run with neither output nor checkpoints, as a stage test runs it
  const io::CheckpointCounts none = explicit_dynamics::run_to_end(whole, spec, whole.history, {});
  CHECK(none.written == 0);
  REQUIRE(whole.finished);
  CHECK(whole.report.completed());
  CHECK(whole.report.steps == 21);
  // t = 0, every 0.25 to 2.0, and the end: 10 rows; fields at 0, 0.5, .. 2.0 and the end.
  CHECK(whole.history.rows().size() == 10);
  const std::vector<double> fields{0.0, 0.5, 1.0, 1.5, 2.0, 2.05};
  REQUIRE(whole.written.size() == fields.size());
  for (std::size_t k = 0; k < fields.size(); ++k) CHECK(whole.written[k] == Approx(fields[k]));
  {
    io::OutputDirectory out(dir);
    Walk w;
    w.history.append({-1.0, 0.0}); // a row before the loop, as a stage's replayed preload
    const io::CheckpointCounts counts =
        explicit_dynamics::run_to_end(w, spec, w.history, {&out, dir, {}, &settings, nullptr});
    CHECK(out.opened());        // history.csv is being written as the run goes
    CHECK(counts.written == 2); // at t = 0.7 and 1.4
    CHECK(counts.restarted_at < 0.0);
    CHECK(w.report.steps == 21);
    CHECK(w.x == whole.x);
    w.history.write(out);
    out.commit();
  }
  const std::vector<std::string> csv = lines_of(dir + "/history.csv");
  REQUIRE(csv.size() == 12); // the header, the row before the loop and the run's 10
  CHECK(csv[0] == "time,x");
  CHECK(csv[1].rfind("-1,", 0) == 0);

  // A restart from the last checkpoint (t = 1.4, step 14) ends where the whole run ends.
  const io::Restart restart = io::find_restart(dir, settings, 1, spec.end_time);
  CHECK(restart.time == Approx(1.4));
  Walk resumed;
  const io::CheckpointCounts counts = explicit_dynamics::run_to_end(
      resumed, spec, resumed.history, {nullptr, dir, {}, &settings, &restart});
  CHECK(counts.restarted_at == restart.time);
  CHECK(counts.written == 0); // the next one would be at 2.1, after the end
  CHECK(resumed.report.steps == whole.report.steps);
  CHECK(resumed.report.steps_timed == whole.report.steps - 14);
  CHECK(resumed.x == whole.x);
  CHECK(resumed.written == whole.written);
  CHECK(resumed.history.rows().size() == 11); // the streamed run's rows, the first one included
  for (std::size_t k = 1; k < resumed.history.rows().size(); ++k)
    CHECK(resumed.history.rows()[k] == whole.history.rows()[k - 1]);
  std::filesystem::remove_all(dir);
}
