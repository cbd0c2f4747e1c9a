// SPH boundary conditions as objects (sph/condition.hpp): the forces and accelerations of each
// kind against their closed forms, the order of the sum, a rank's part of a whole body's
// condition, copies, the event's loads set aside, and the checkpoint hook.
#include "meshfree/io/state_file.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/rates.hpp"
#include "meshfree/sph/surface_force.hpp"
#include "meshfree/sph/surface_load.hpp"
#include "meshfree/sph/transmitting_boundary.hpp"
#include "sph_test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

using namespace mf;

namespace {

/// Four particles at rest on the x axis, masses 1, 2, 3, 4 kg (volume 1e-3 m^3, density m / V).
sph::Hydro four_particles() {
  sph::Hydro h;
  h.dim = 1;
  h.materials.push_back(test_solid());
  for (int k = 0; k < 4; ++k) {
    const double x[3] = {0.1 * k, 0.0, 0.0};
    add(h, x, 1e-3, (k + 1) / 1e-3, 0.0, 0.15, 0);
  }
  return h;
}

/// A pressure history p(t) = P (1 - t / t_d) (Friedlander with b = 0, arriving at t = 0).
loads::Friedlander ramp_down(double peak) {
  return {0.0, 1e-3, peak, 0.0};
}

sph::SurfaceLoad load_on(std::vector<int> particles, double peak) {
  sph::SurfaceLoad l;
  l.name = "blast";
  l.particles = std::move(particles);
  for (std::size_t k = 0; k < l.particles.size(); ++k) {
    l.area.push_back(0.01 * (k + 1));
    l.pulses.push_back(ramp_down(peak));
  }
  l.direction[0] = 1.0;
  return l;
}

sph::TransmittingBoundary dashpots_on(std::vector<int> particles) {
  sph::TransmittingBoundary b;
  b.name = "far";
  b.particles = std::move(particles);
  for (std::size_t k = 0; k < b.particles.size(); ++k) {
    b.area.push_back(0.01);
    b.normal_impedance.push_back(1.0e7 * (k + 1));
    b.shear_impedance.push_back(5.0e6 * (k + 1));
    b.static_force.insert(b.static_force.end(), {100.0 * (k + 1), -50.0, 0.0});
  }
  b.normal[0] = 1.0;
  return b;
}

/// A condition with state of its own: the impulse it has given, which a checkpoint keeps.
struct Counting final : sph::Condition {
  std::string name = "counting";
  double impulse = 0.0;
  std::vector<double> per_particle{1.0, 2.0};
  std::vector<int> hits{3};
  long calls = 0;
  std::unique_ptr<sph::Condition> clone() const override {
    return std::make_unique<Counting>(*this);
  }
  const std::string& label() const override { return name; }
  int order() const override { return 1; }
  void add_accelerations(const sph::Hydro&, double, std::vector<double>&) const override {}
  void append_forces(const sph::Hydro&, double, std::vector<int>&,
                     std::vector<double>&) const override {}
  std::unique_ptr<sph::Condition> owned_part(const particles::ParticleSet&) const override {
    return clone();
  }
  void for_each_state(const sph::StateVisitor& visit) override {
    visit("impulse", impulse), visit("per_particle", per_particle), visit("hits", hits);
    visit("calls", calls);
  }
};

/// A visitor that collects the names a state is visited under.
struct Names {
  std::set<std::string>& names;
  std::string prefix;
  template <class T> void operator()(const std::string& name, const T&) const {
    names.insert(prefix + name);
  }
  template <class T> void operator()(const particles::FieldInfo& f, const T&) const {
    names.insert(prefix + f.name);
  }
  Names operator/(const std::string& part) const { return {names, prefix + part + "."}; }
};

} // namespace

TEST_CASE("SPH conditions: each kind's forces and accelerations are its closed form",
          "[sph][conditions]") {
  sph::Hydro h = four_particles();
  h.particles.time = 0.25e-3; // p = 0.75 P
  h.particles.v[3 * 3] = 2.0, h.particles.v[3 * 3 + 1] = -1.0;
  h.conditions.add(dashpots_on({3}));
  h.conditions.add(load_on({0, 1}, 1e5));
  sph::SurfaceForce held;
  held.name = "held", held.particles = {1, 3}, held.force = {10.0, 0.0, 0.0, 0.0, -20.0, 0.0};
  h.conditions.add(held);
  // Kept in the order of the sum whatever the order they were added in.
  REQUIRE(h.conditions.size() == 3);
  CHECK(h.conditions[0].label() == "blast");
  CHECK(h.conditions[1].label() == "held");
  CHECK(h.conditions[2].label() == "far");

  std::vector<int> who;
  std::vector<double> force;
  sph::external_forces(h, who, force);
  // Load: 0.75 P A_k along x; held force as given; dashpot -A (Z_n v_n n + Z_s v_t) + static.
  const std::vector<int> who_expected{0, 1, 1, 3, 3};
  const std::vector<double> expected{0.75e5 * 0.01,
                                     0,
                                     0,
                                     0.75e5 * 0.02,
                                     0,
                                     0,
                                     10,
                                     0,
                                     0,
                                     0,
                                     -20,
                                     0,
                                     -0.01 * 1e7 * 2 + 100,
                                     -0.01 * 5e6 * -1.0 - 50,
                                     0};
  REQUIRE(who == who_expected);
  REQUIRE(force.size() == expected.size());
  for (std::size_t k = 0; k < force.size(); ++k)
    CHECK(std::abs(force[k] - expected[k]) <= 1e-12 * std::max(1.0, std::abs(expected[k])));

  // Accelerations: the same forces over each particle's mass, summed per particle.
  std::vector<double> dv(12, 0.0), sum(12, 0.0);
  for (std::size_t c = 0; c < h.conditions.size(); ++c)
    h.conditions[c].add_accelerations(h, h.particles.time, dv);
  for (std::size_t e = 0; e < who.size(); ++e)
    for (int d = 0; d < 3; ++d) sum[3 * who[e] + d] += force[3 * e + d];
  for (int i = 0; i < 4; ++i)
    for (int d = 0; d < 3; ++d)
      CHECK(std::abs(dv[3 * i + d] - sum[3 * i + d] / h.particles.mass[i]) <=
            1e-14 * std::max(1.0, std::abs(dv[3 * i + d])));

  // A fixed particle takes no load and no held force.
  h.fields.fixed[1] = 1;
  sph::external_forces(h, who, force);
  CHECK(std::count(who.begin(), who.end(), 1) == 0);
  CHECK(who.size() == 3);
  // The scale of the held forces: the largest held force or static force on one particle.
  double largest = 0.0;
  for (std::size_t c = 0; c < h.conditions.size(); ++c)
    largest = std::max(largest, h.conditions[c].largest_held_force());
  CHECK(largest == Approx(std::hypot(100.0, 50.0)).epsilon(1e-15));
}

TEST_CASE("SPH conditions: a rank's part of a whole body's condition", "[sph][conditions]") {
  // The rank owns global ids 1 and 3 (as particles 0 and 1).
  particles::ParticleSet P;
  for (int k = 0; k < 2; ++k) P.add(Vec3(k, 0, 0), 1.0, 1.0, 0);
  P.id = {1, 3};
  const sph::SurfaceLoad load = load_on({3, 0, 1, 2}, 1e5);
  const auto part = load.owned_part(P);
  const auto& mine = dynamic_cast<const sph::SurfaceLoad&>(*part);
  CHECK(mine.particles == std::vector<int>{1, 0}); // ids 3 and 1, in the whole's order
  CHECK(mine.area == std::vector<double>{0.01, 0.03});
  CHECK(mine.pulses.size() == 2);
  CHECK(mine.name == "blast");
  CHECK(mine.direction[0] == 1.0);

  const sph::TransmittingBoundary b = dashpots_on({0, 1, 2, 3});
  const auto bpart = b.owned_part(P);
  const auto& bmine = dynamic_cast<const sph::TransmittingBoundary&>(*bpart);
  CHECK(bmine.particles == std::vector<int>{0, 1});
  CHECK(bmine.normal_impedance == std::vector<double>{2e7, 4e7});
  CHECK(bmine.shear_impedance == std::vector<double>{1e7, 2e7});
  CHECK(bmine.static_force == std::vector<double>{200, -50, 0, 400, -50, 0});
  sph::TransmittingBoundary bare = b;
  bare.static_force.clear();
  const auto barepart = bare.owned_part(P);
  CHECK(dynamic_cast<const sph::TransmittingBoundary&>(*barepart).static_force.empty());

  sph::SurfaceForce f;
  f.name = "held", f.particles = {2, 3}, f.force = {1, 2, 3, 4, 5, 6};
  const auto fpart = f.owned_part(P);
  const auto& fmine = dynamic_cast<const sph::SurfaceForce&>(*fpart);
  CHECK(fmine.particles == std::vector<int>{1});
  CHECK(fmine.force == std::vector<double>{4, 5, 6});

  // The list keeps the whole body's conditions and cuts its part again when particles move.
  sph::Conditions list;
  list.add(f);
  list.add(load);
  list.keep_whole(P);
  REQUIRE(list.size() == 2);
  CHECK(dynamic_cast<const sph::SurfaceLoad&>(list[0]).particles == std::vector<int>{1, 0});
  P.id = {0, 2};
  list.cut(P);
  CHECK(dynamic_cast<const sph::SurfaceLoad&>(list[0]).particles == std::vector<int>{0, 1});
  CHECK(dynamic_cast<const sph::SurfaceLoad&>(list[0]).area == std::vector<double>{0.02, 0.04});
  CHECK(dynamic_cast<const sph::SurfaceForce&>(list[1]).particles == std::vector<int>{1});
  CHECK(dynamic_cast<const sph::SurfaceForce&>(list[1]).force == std::vector<double>{1, 2, 3});
}

TEST_CASE("SPH conditions: copies are deep and the event's loads step aside", "[sph][conditions]") {
  sph::Hydro h = four_particles();
  h.conditions.add(load_on({0}, 1e5));
  sph::SurfaceForce held;
  held.name = "held", held.particles = {2}, held.force = {1.0, 0.0, 0.0};
  h.conditions.add(held);
  const sph::Hydro copy = h;
  h.conditions.of_kind<sph::SurfaceForce>()[0]->force[0] = 7.0;
  CHECK(copy.conditions.of_kind<sph::SurfaceForce>()[0]->force[0] == 1.0);

  sph::Conditions event = h.conditions.take_event_loads();
  REQUIRE(event.size() == 1);
  CHECK(event[0].label() == "blast");
  REQUIRE(h.conditions.size() == 1);
  CHECK(h.conditions[0].label() == "held");
  h.conditions.add_all(std::move(event));
  REQUIRE(h.conditions.size() == 2);
  CHECK(h.conditions[0].label() == "blast"); // back before the held forces
}

TEST_CASE("SPH conditions: a condition's own state goes through a checkpoint's visitor",
          "[sph][conditions][checkpoint]") {
  sph::Conditions list;
  Counting& c = list.add(Counting{});
  c.impulse = 2.5, c.per_particle = {4.0, 5.0, 6.0}, c.hits = {1, 2}, c.calls = 9;
  std::vector<char> bytes;
  list.for_each_state(io::Packer{bytes});
  c.impulse = 0.0, c.per_particle.clear(), c.hits.clear(), c.calls = 0;
  std::size_t at = 0;
  list.for_each_state(io::Unpacker{bytes, at});
  CHECK(at == bytes.size());
  CHECK(c.impulse == 2.5);
  CHECK(c.per_particle == std::vector<double>{4.0, 5.0, 6.0});
  CHECK(c.hits == std::vector<int>{1, 2});
  CHECK(c.calls == 9);

  // The kinds of the solver keep no state of their own, so a run's checkpoint keeps the names
  // it kept before the conditions were objects.
  sph::Hydro h = four_particles();
  h.conditions.add(load_on({0}, 1e5));
  h.conditions.add(dashpots_on({3}));
  std::set<std::string> names;
  h.for_each_state(Names{names, ""});
  CHECK(names.count("damping") == 1);
  CHECK(names.count("external_work") == 1);
  for (const std::string& n : names) CHECK(n.rfind("conditions", 0) != 0);
}
