// The pieces every explicit analysis shares: the time loop's output schedule and its stop on a
// non-finite state, gauges, particle lattices, the particle set's owned and ghost ranges, and
// the summary.json and history.csv writer.
#include "field_registry_support.hpp"
#include "hdf5_read.hpp"
#include "meshfree/explicit/gauges.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/geometry/lattice.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/io/state_file.hpp"
#include "meshfree/particles/particle_set.hpp"
#include "meshfree/pd/particle_order.hpp"
#include "meshfree/sph/particle_fields.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

using namespace mf;

namespace {

/// One particle moving at unit speed; its motion turns non-finite at `breaks_at` (if set).
struct Drift {
  double t = 0.0, x = 0.0, breaks_at = -1.0;
  long n = 0;
  std::vector<double> recorded, written;
  double time() const { return t; }
  long step() const { return n; }
  bool time_step(double remaining, double& dt, std::string&) const {
    dt = std::min(0.1, remaining);
    return true;
  }
  void advance(double dt, bool) {
    t += dt;
    ++n;
    x = breaks_at >= 0.0 && t > breaks_at ? std::numeric_limits<double>::quiet_NaN() : x + dt;
  }
  void track() {}
  int nonfinite() const { return std::isfinite(x) ? -1 : 0; }
  Vec3 position(int) const { return {1.0, 2.0, 3.0}; }
  std::string advice() const { return "advice"; }
  void record() { recorded.push_back(t); }
  void write_fields() { written.push_back(t); }
  std::string progress() const { return "x " + std::to_string(x); }
  void save(io::Checkpoints&, const io::Saver& save) {
    save("t", t), save("x", x), save("n", n), save("recorded", recorded);
    save("written", written);
  }
  void restore(const io::Loader& load) {
    load("t", t), load("x", x), load("n", n), load("recorded", recorded);
    load("written", written);
  }
};

} // namespace

TEST_CASE("a loop restarted from its checkpoint goes on as the run it came from",
          "[explicit][checkpoint]") {
  const std::string dir = "test_loop_checkpoint";
  std::filesystem::remove_all(dir);
  const explicit_dynamics::Schedule schedule{2.05, 0.25, 0.5};
  Drift whole;
  const explicit_dynamics::LoopReport all = explicit_dynamics::run_time_loop(whole, schedule);
  // The same run with a checkpoint every 0.7: the last one, at t = 1.4 (step 14), stays.
  {
    Drift first;
    io::Checkpoints checkpoints(dir, {}, {0.7, 0.0}, {{"time.end", "2.05"}});
    explicit_dynamics::run_time_loop(first, schedule, &checkpoints);
    CHECK(checkpoints.counts().written == 2);
  }
  const io::Restart restart = io::find_restart(dir, {{"time.end", "3.0"}}, 1, 3.0);
  CHECK(restart.step == 14);
  CHECK(restart.time == Approx(1.4));
  Drift resumed;
  const auto state = restart.open(0);
  const explicit_dynamics::LoopReport rest =
      explicit_dynamics::run_time_loop(resumed, schedule, nullptr, state.get());
  CHECK(rest.steps == all.steps);
  CHECK(rest.steps_timed == all.steps - 14);
  CHECK(resumed.recorded == whole.recorded);
  CHECK(resumed.written == whole.written);
  CHECK(resumed.x == whole.x);
  // A key other than the end time and the output intervals may not change.
  CHECK_THROWS_WITH(io::find_restart(dir, {{"time.end", "2.05"}, {"materials.0.E", "1"}}, 1, 2.05),
                    Catch::Contains("materials.0.E changed since the checkpoint"));
  CHECK_THROWS_WITH(io::find_restart(dir, {{"time.end", "2.05"}}, 2, 2.05),
                    Catch::Contains("restart it on as many"));
  // A checkpoint after the run's end is not this run's.
  CHECK_THROWS_AS(io::find_restart(dir, {{"time.end", "1.0"}}, 1, 1.0), io::CheckpointRefused);
  // Every array passes its checksum, and one the run built comes back at its length only.
  CHECK_NOTHROW(restart.verify());
  const io::Loader load{*state, ""};
  std::vector<double> two(2);
  CHECK_THROWS_WITH(load("recorded", two),
                    Catch::Contains("checkpoint holds 6 values of 'recorded', this run has 2"));
  io::remove_checkpoints(dir);
  CHECK_FALSE(std::filesystem::exists(dir + "/checkpoint"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("the explicit time loop records on its schedule and at the end", "[explicit]") {
  Drift m;
  const explicit_dynamics::LoopReport r = explicit_dynamics::run_time_loop(m, {1.05, 0.25, 0.5});
  CHECK(r.completed());
  CHECK(r.steps == 11);
  // Rows at 0, at the first step at or past each 0.25, and at the end.
  REQUIRE(m.recorded.size() == 6);
  CHECK(m.recorded[1] == Approx(0.3));
  CHECK(m.recorded[4] == Approx(1.0));
  CHECK(m.recorded.back() == Approx(1.05));
  REQUIRE(m.written.size() == 4); // 0, 0.5, 1.0 and the end
  CHECK(m.written[1] == Approx(0.5));
  CHECK(m.written.back() == Approx(1.05));
}

TEST_CASE("an end time on the field interval gives one field step there", "[explicit]") {
  // Two steps with one time leave ParaView's XDMF readers an empty last frame.
  Drift m;
  REQUIRE(explicit_dynamics::run_time_loop(m, {1.0, 0.25, 0.5}).completed());
  REQUIRE(m.written.size() == 3); // 0, 0.5 and the end
  CHECK(m.written[1] == Approx(0.5));
  CHECK(m.written[2] == Approx(1.0));
  CHECK(m.time() == m.written[2]);
}

TEST_CASE("the explicit time loop stops where the state stops being finite", "[explicit]") {
  Drift m;
  m.breaks_at = 0.45;
  const explicit_dynamics::LoopReport r = explicit_dynamics::run_time_loop(m, {1.0, 0.0, 0.0});
  CHECK(r.status == "failed");
  CHECK(r.stop_reason.find("step 5") != std::string::npos);
  CHECK(r.stop_reason.find("particle 0 at (1, 2, 3)") != std::string::npos);
  CHECK(r.stop_reason.find("advice") != std::string::npos);
  CHECK(m.recorded.size() == 5); // t = 0 to 0.4, every step; nothing after the stop
  CHECK(m.written.size() == 1);
}

TEST_CASE("gauges follow the nearest particle and keep maxima over every step", "[explicit]") {
  const std::vector<double> x = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  explicit_dynamics::Gauges g({{"a", Vec3(0.9, 0.1, 0.0)}, {"b", Vec3(5.0, 0.0, 0.0)}}, x, 3);
  CHECK(g.particles() == std::vector<int>{1, 2});
  std::vector<double> value = {0.0, -3.0, 1.0};
  g.record("q", [&](int i) { return value[i]; });
  g.track("q", [&](int i) { return value[i]; });
  CHECK(g.columns() == std::vector<std::string>{"a_q", "b_q"});
  g.update_maxima();
  value = {0.0, 2.0, 4.0};
  g.update_maxima();
  CHECK(g.maxima()[0].second == 3.0);
  CHECK(g.maxima()[1].second == 4.0);
  std::vector<double> row;
  g.append_to(row);
  CHECK(row == std::vector<double>{2.0, 4.0});
}

TEST_CASE("lattices of a spacing and fitted to a box", "[explicit][geometry]") {
  const auto l = geometry::Lattice::of_spacing({0, 0, 5}, {1.04, 0.5, 9}, 0.1, 2);
  CHECK(l.count[0] == 10);
  CHECK(l.count[1] == 5);
  CHECK(l.count[2] == 1);
  CHECK(l.centre(9, 4, 0).isApprox(Vec3(0.95, 0.45, 0.0)));
  const auto f = geometry::Lattice::fitted({0, 0, 0}, {1.04, 0.5, 0.3}, 0.1, 3);
  CHECK(f.step(0) == Approx(0.104));
  CHECK(f.cell_volume(3) == Approx(0.104 * 0.1 * 0.1));
  long cells = 0;
  f.for_each([&](const Vec3&) { ++cells; });
  CHECK(cells == 150);
  double area = 0.0;
  geometry::for_each_ring_point({0, 0, 0}, 1.0, 2.0, 0.1,
                                [&](const Vec3&, double a) { area += a; });
  CHECK(area == Approx(M_PI * 3.0));
}

TEST_CASE("ghost particles follow the owned ones", "[explicit][particles]") {
  particles::ParticleSet p;
  p.add({1, 2, 3}, 0.5, 2.0, 1);
  p.add({4, 5, 6}, 0.5, 2.0, 0);
  p.u[3] = 1.0;
  CHECK(p.position(1).isApprox(Vec3(5, 5, 6)));
  CHECK(p.mass[0] == 1.0);
  const int g = p.add_ghost(1);
  CHECK(g == 2);
  CHECK(p.owned().size() == 2);
  CHECK(p.ghosts().first() == 2);
  CHECK(p.all().size() == 3);
  CHECK(p.position(2).isApprox(p.position(1)));
  p.drop_ghosts();
  CHECK(p.size() == 2);
  CHECK(p.ghosts().size() == 0);
}

TEST_CASE("the particle registries name each array once and write scalars and vectors only",
          "[explicit][particles]") {
  std::set<std::string> written;
  const auto check = [&written](auto registry) {
    std::set<std::string> names;
    registry([&](const particles::FieldInfo& f, auto) {
      INFO(f.name);
      REQUIRE(names.insert(f.name).second);
      REQUIRE(f.components >= 1);
      if (f.output) REQUIRE((f.components == 1 || f.components == 3));
      if (f.output) REQUIRE(written.insert(f.output).second); // one fields.h5 for both
    });
  };
  check([](auto&& visit) { particles::ParticleSet::for_each_member(visit); });
  check([](auto&& visit) { sph::ParticleFields::for_each_member(visit); });
  CHECK(written == std::set<std::string>{"displacement", "velocity", "material", "density",
                                         "specific_energy", "smoothing_length", "pressure",
                                         "plastic_strain", "damage", "failed"});
}

TEST_CASE("a ghost copy, a cut and a reordering carry every registered array of a particle",
          "[explicit][particles]") {
  particles::ParticleSet p;
  sph::ParticleFields f;
  for (int i = 0; i < 5; ++i) p.add({1.0 * i, 0, 0}, 1.0, 1.0, 0), f.add(1.0, 0.0, 1.0, false);
  fill_distinct(p, p.size());
  fill_distinct(f, p.size());
  const int g = p.add_ghost(2);
  f.append_copy(2);
  require_same_particle(p, g, p, 2);
  // SPH's copy is a mirror image: fixed, and otherwise its source.
  REQUIRE(f.fixed[g] == 1);
  f.fixed[g] = f.fixed[2];
  require_same_particle(f, g, f, 2);
  p.add_ghost(4);
  p.drop_ghosts_from(g + 1);
  f.truncate(g + 1);
  const auto six = [](const particles::FieldInfo& info, const auto& a) {
    INFO(info.name);
    REQUIRE(a.size() == static_cast<std::size_t>(info.components) * 6);
  };
  p.for_each_field(six);
  f.for_each_field(six);
  // Reordered along the space-filling curve: particle k is particle order[k] of before, every
  // array with it, and ids are numbered again.
  particles::ParticleSet q;
  for (int i = 0; i < 6; ++i) q.add({0, 0, 0}, 1.0, 1.0, 0);
  fill_distinct(q, q.size());
  for (int i = 0; i < q.size(); ++i) q.X[3 * i] = q.X[3 * i + 1] = q.X[3 * i + 2] = 6.0 - i;
  const particles::ParticleSet before = q;
  const std::vector<int> order = pd::order_along_curve(q, 1.0);
  REQUIRE(order == std::vector<int>{5, 4, 3, 2, 1, 0});
  for (int k = 0; k < q.size(); ++k) {
    REQUIRE(q.id[k] == k);
    particles::ParticleSet::for_each_member([&](const particles::FieldInfo& info, auto m) {
      if (std::string(info.name) == "id") return;
      INFO(info.name);
      for (int c = 0; c < info.components; ++c)
        REQUIRE((q.*m)[info.components * k + c] == (before.*m)[info.components * order[k] + c]);
    });
  }
}

TEST_CASE("a checkpoint keeps every registered array of a particle and refuses a broken one",
          "[explicit][particles][checkpoint]") {
  const std::string dir = "test_particle_registry";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  particles::ParticleSet p;
  sph::ParticleFields f;
  for (int i = 0; i < 5; ++i) p.add({1.0 * i, 0, 0}, 1.0, 1.0, 0), f.add(1.0, 0.0, 1.0, false);
  p.add_ghost(1), f.append_copy(1);
  p.add_ghost(3), f.append_copy(3);
  fill_distinct(p, p.size());
  fill_distinct(f, p.size());
  p.time = 0.25, p.step = 7;
  const auto save = [&dir](const std::string& name, particles::ParticleSet& ps,
                           sph::ParticleFields& fs) {
    io::StateWriter out(dir + "/" + name);
    ps.for_each_state(io::Saver{out, ""} / "particles");
    fs.for_each_state(io::Saver{out, ""} / "fields");
    out.close();
  };
  save("state.h5", p, f);
  const io::StateReader in(dir + "/state.h5");
  SECTION("read back whole, as a rank whose particles move (SPH)") {
    particles::ParticleSet q;
    sph::ParticleFields g;
    const io::Loader load{in, "", true};
    q.for_each_state(load / "particles");
    g.for_each_state(load / "fields");
    require_same(q, p);
    require_same(g, f);
    REQUIRE(q.time == 0.25);
    REQUIRE(q.step == 7);
    REQUIRE(q.owned_count() == 5);
    REQUIRE(q.ghosts().size() == 2);
  }
  SECTION("read back over the set-up's particles (peridynamics): what the set-up made is kept") {
    particles::ParticleSet q = p;
    q.for_each_field([](const particles::FieldInfo&, auto& a) {
      for (auto& x : a) x = static_cast<std::decay_t<decltype(x)>>(x + 1);
    });
    particles::for_each_kept(q, io::Loader{in, "particles."}, particles::kSetUp);
    require_same(q, p, particles::kSetUp);
    REQUIRE(q.X[0] == p.X[0] + 1); // not read
    REQUIRE(q.u[0] == p.u[0]);
    particles::ParticleSet more = p;
    more.add_ghost(0);
    REQUIRE_THROWS_AS(
        particles::for_each_kept(more, io::Loader{in, "particles."}, particles::kSetUp),
        io::CheckpointRefused);
  }
  SECTION("an array that does not hold whole particles is refused") {
    sph::ParticleFields bad = f;
    bad.S.push_back(0.5);
    save("bad.h5", p, bad);
    const io::StateReader bad_in(dir + "/bad.h5");
    sph::ParticleFields g;
    REQUIRE_THROWS_WITH(g.for_each_state(io::Loader{bad_in, "fields.", true}),
                        Catch::Contains("values of 'fields.S', not a whole number of particles "
                                        "of 6 values"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("summary.json keeps the header, status, sections and timers in order", "[explicit][io]") {
  io::Summary s({"p", "d", "SI", "sph", ""});
  s.set_status("failed", "why");
  s.set("openmp_threads", 2);
  s.section("counts").set("particles", 3);
  s.section("results").set("peak", 1.5);
  s.section("time_s").set("extra", 0.25);
  PhaseTimer timer;
  timer.add("stepping", 1.0);
  const std::string j = s.str(timer);
  std::size_t at = 0;
  for (const char* key : {"\"problem\"", "\"description\"", "\"units\"", "\"analysis\"",
                          "\"status\"", "\"stop_reason\"", "\"openmp_threads\"", "\"counts\"",
                          "\"time_s\"", "\"stepping\"", "\"extra\"", "\"total\"", "\"results\""}) {
    const std::size_t k = j.find(key, at);
    INFO(key << " in " << j);
    REQUIRE(k != std::string::npos);
    at = k;
  }
  CHECK(j.find("\"method\"") == std::string::npos);
  io::History h({"time", "x"});
  h.append({0.0, -2.0});
  h.append({1.0, 1.0});
  CHECK(h.max_abs(1) == 2.0);
}

TEST_CASE("a field series writes each field's values of the moment, in place or copied",
          "[explicit][io]") {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "meshfree_field_values").string();
  std::filesystem::remove_all(dir);
  std::vector<double> xyz{0, 0, 0, 1, 0, 0}, speed{1.0, 2.0}, velocity(6, 0.5);
  std::vector<int> count{3, 4};
  {
    io::OutputDirectory out(dir);
    io::FieldOutput fields(&out, "fields", xyz);
    fields.scalar("speed", speed);       // doubles: written where they lie
    fields.vector("velocity", velocity); // three a point, in place too
    fields.scalar("count", count);       // other types: copied as doubles
    fields.scalar("twice", [&](std::vector<double>& v) { v = {2 * speed[0], 2 * speed[1]}; });
    fields.write(0.0);
    speed = {5.0, -6.0}, velocity[4] = -7.0, count = {8, 9};
    fields.write(1.0);
    fields.close();
    out.commit();
  }
  const std::string h5 = dir + "/fields.h5";
  CHECK(read_doubles(h5, "/step_000000/speed") == std::vector<double>{1.0, 2.0});
  CHECK(read_doubles(h5, "/step_000001/speed") == std::vector<double>{5.0, -6.0});
  CHECK(read_doubles(h5, "/step_000000/velocity") == std::vector<double>(6, 0.5));
  CHECK(read_doubles(h5, "/step_000001/velocity") ==
        std::vector<double>{0.5, 0.5, 0.5, 0.5, -7.0, 0.5});
  CHECK(read_doubles(h5, "/step_000000/count") == std::vector<double>{3.0, 4.0});
  CHECK(read_doubles(h5, "/step_000001/count") == std::vector<double>{8.0, 9.0});
  CHECK(read_doubles(h5, "/step_000001/twice") == std::vector<double>{10.0, -12.0});
  std::filesystem::remove_all(dir);
}
