// Bodies from loops of segments and arcs (Domain::from_loops, OutlineHole::loop_of), the form a
// body read from a file takes: traced from a built-in body's own boundary (rounded corners,
// convex and re-entrant, a rounded end, holes of every kind), in either sense, the loop body is
// the built-in body: the same points inside at a grid of points off the boundary and on the
// arcs' chords, the same area, bounds, boundary length and distances, the same selections by
// name, and a cloud whose shape functions reproduce a linear field. Loops that are open, sweep an
// arc past a half turn or enclose nothing are refused. A body of one whole circle about a
// concentric circle hole is known as a ring (annulus_of), which particle layers fill by rings.
#include "boundary_walk.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/geometry/outline_file.hpp"
#include "shape_reproduction.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;
using geometry::Curve;
using geometry::Domain;
using geometry::OutlineHole;

namespace {

const double pi = std::acos(-1.0);

struct Case {
  const char* what;
  Domain body;
};

std::vector<Case> cases() {
  Domain bar = Domain::polygon({{0, 0}, {20, 0}, {20, 2.5}, {10, 2.5}, {10, 5}, {0, 5}},
                               {"symmetry", "right", "narrow_top", "shoulder", "top", "left"});
  bar.round_corner({10, 2.5}, 1.0, "fillet");
  Domain rounded_end = Domain::rectangle({0, 0}, {4, 1});
  rounded_end.round_corner({4, 0}, 0.5, "end_low");
  rounded_end.round_corner({4, 1}, 0.5, "end_high");
  Domain plate = Domain::rectangle({0, 0}, {6, 3});
  plate.round_corner({0, 3}, 0.4);
  plate.add_hole(OutlineHole::slot({1.5, 1.5}, {3.0, 1.5}, 0.4, "slot"));
  plate.add_hole(OutlineHole::polygon({{4, 1}, {5, 1}, {5, 2}, {4, 2}}, "window"));
  plate.add_hole(geometry::Circle{{5.0, 0.6}, 0.3, "bore"});
  Domain lug = Domain::polygon({{0, 0}, {3, 0}, {3, 2}, {0, 2}});
  lug.round_corner({3, 0}, 1.0, "lug_low");
  lug.round_corner({3, 2}, 1.0, "lug_high");
  lug.add_hole(OutlineHole::slot({2.0, 1.0}, {2.0, 1.0}, 0.5, "pin"));
  return {{"the filleted bar: a re-entrant fillet", bar},
          {"a bar with a rounded end: two fillets take its whole end", rounded_end},
          {"a plate with a rounded corner, a slot, a window and a bore", plate},
          {"a lug: a half-round end, a pin hole that is a slot of no length", lug}};
}

/// The built-in body traced as loops: its outline, and every hole but the circles (which stay
/// circles) as a loop.
Domain traced(const Domain& d, bool other_sense) {
  std::vector<std::vector<Curve>> holes;
  for (const OutlineHole& h : d.outline_holes())
    holes.push_back(other_sense ? geometry::reversed(h.loop()) : h.loop());
  const std::vector<Curve>& outline = d.outline();
  Domain loops = Domain::from_loops(other_sense ? geometry::reversed(outline) : outline, holes);
  for (const geometry::Circle& c : d.holes()) loops.add_hole(c);
  return loops;
}

} // namespace

TEST_CASE("curve loops: a body traced from a built-in body's boundary is that body",
          "[loops][geometry]") {
  for (const Case& c : cases())
    for (const bool other_sense : {false, true}) {
      INFO(c.what << (other_sense ? ", traced in the other sense" : ""));
      const Domain& d = c.body;
      const Domain loops = traced(d, other_sense);
      CHECK(loops.has_arcs());
      CHECK(loops.area_estimate() == Approx(d.area_estimate()).epsilon(1e-12));
      CHECK((loops.bounds().lo - d.bounds().lo).norm() < 1e-12);
      CHECK((loops.bounds().hi - d.bounds().hi).norm() < 1e-12);
      CHECK(walk_boundary(loops, true) == Approx(walk_boundary(d, true)).epsilon(1e-12));
      const BoundingBox b = d.bounds();
      const double scale = b.size().maxCoeff();
      int compared = 0;
      for (int j = 0; j <= 97; ++j)
        for (int i = 0; i <= 211; ++i) {
          const Vec2 p = b.lo - 0.05 * b.size() +
                         Vec2(1.1 * b.size().x() * i / 211.0, 1.1 * b.size().y() * j / 97.0);
          CHECK(loops.distance_to_boundary(p) == Approx(d.distance_to_boundary(p)).margin(1e-12));
          if (d.distance_to_boundary(p) < 1e-9 * scale) continue;
          ++compared;
          if (loops.contains(p) != d.contains(p)) FAIL_CHECK("differ at " << p.transpose());
        }
      CHECK(compared > 20000);
      // Points on an arc's chord: on an edge of the loop's polygon, yet off the boundary.
      for (const Curve& piece : d.boundary())
        for (double t = 0.05; piece.kind == Curve::Kind::Arc && t < 1.0; t += 0.1) {
          const Vec2 p = piece.point(0.0) + t * (piece.point(1.0) - piece.point(0.0));
          if (loops.contains(p) != d.contains(p))
            FAIL_CHECK("differ on a chord at " << p.transpose());
        }
      for (const Curve& piece : d.boundary())
        CHECK(loops.names_selected(piece.name) == d.names_selected(piece.name));
      for (const char* side : {"x_min", "x_max", "y_min", "y_max"})
        CHECK(loops.names_selected(side) == d.names_selected(side));
      const CloudCheck cloud = check_cloud(loops, 0.1 * std::min(b.size().x(), b.size().y()));
      CHECK(cloud.outside == 0);
      CHECK(cloud.reproduction < 1e-10);
    }
}

TEST_CASE("curve loops: open loops, arcs past a half turn and loops of no area are refused",
          "[loops][geometry]") {
  const auto segment = [](Vec2 a, Vec2 b) {
    Curve c;
    c.name = "edge";
    c.a = a;
    c.b = b;
    return c;
  };
  const std::vector<Curve> square{segment({0, 0}, {1, 0}), segment({1, 0}, {1, 1}),
                                  segment({1, 1}, {0, 1}), segment({0, 1}, {0, 0})};
  CHECK(Domain::from_loops(square, {}).area_estimate() == Approx(1.0));
  std::vector<Curve> open = square;
  open[2].a = Vec2(1.0, 1.01);
  CHECK_THROWS_WITH(Domain::from_loops(open, {}), Catch::Contains("the loop is open"));
  Curve arc;
  arc.kind = Curve::Kind::Arc;
  arc.name = "round";
  arc.center = Vec2(0.5, 1.2); // from (1, 1) the long way round, over the top, to (0, 1)
  arc.radius = std::hypot(0.5, 0.2);
  arc.theta0 = std::atan2(-0.2, 0.5);
  arc.theta1 = std::atan2(-0.2, -0.5) + 2.0 * pi;
  std::vector<Curve> wide = square;
  wide[2] = arc;
  CHECK_THROWS_WITH(Domain::from_loops(wide, {}), Catch::Contains("more than a half turn"));
  const std::vector<Curve> flat{segment({0, 0}, {1, 0}), segment({1, 0}, {0, 0})};
  CHECK_THROWS_WITH(Domain::from_loops(flat, {}), Catch::Contains("encloses no area"));
  // A half-round end: the arc from (1, 0) round (1, 0.5) to (1, 1) adds pi / 8 to the square.
  std::vector<Curve> round_end = square;
  arc.center = Vec2(1.0, 0.5);
  arc.radius = 0.5;
  arc.theta0 = -0.5 * pi;
  arc.theta1 = 0.5 * pi;
  round_end[1] = arc;
  const Domain d = Domain::from_loops(round_end, {});
  CHECK(d.area_estimate() == Approx(1.0 + pi / 8.0).epsilon(1e-14));
  CHECK(d.contains({1.45, 0.5}));
  CHECK_FALSE(d.contains({1.45, 0.9}));
  CHECK(walk_boundary(d, true) == Approx(3.0 + 0.5 * pi).epsilon(1e-14));
}

TEST_CASE("curve loops: a body of one whole circle about a concentric circle hole is a ring",
          "[loops][geometry]") {
  // The outline in quarter turns, as a file's circle is read; the ring of a tunnel's lining.
  const auto circle = [](Vec2 centre, double radius) {
    std::vector<Curve> loop;
    for (int k = 0; k < 4; ++k) {
      Curve c;
      c.kind = Curve::Kind::Arc;
      c.name = "outer";
      c.center = centre;
      c.radius = radius;
      c.theta0 = 0.5 * pi * k;
      c.theta1 = 0.5 * pi * (k + 1);
      loop.push_back(c);
    }
    return loop;
  };
  const Vec2 c(0.0, -13.25);
  Domain lining = Domain::from_loops(circle(c, 3.25), {});
  lining.add_hole(geometry::Circle{c, 2.75, "bore"});
  const auto ring = geometry::annulus_of(lining);
  REQUIRE(ring);
  CHECK((ring->center - c).norm() < 1e-12);
  CHECK(ring->inner == 2.75);
  CHECK(ring->outer == 3.25);
  // Not rings: no hole, a hole off the centre, two holes, an outline with a chord.
  CHECK_FALSE(geometry::annulus_of(Domain::from_loops(circle(c, 3.25), {})));
  Domain off = Domain::from_loops(circle(c, 3.25), {});
  off.add_hole(geometry::Circle{c + Vec2(0.1, 0.0), 2.75, "bore"});
  CHECK_FALSE(geometry::annulus_of(off));
  Domain two = lining;
  two.add_hole(geometry::Circle{c + Vec2(0.0, 3.0), 0.1, "drain"});
  CHECK_FALSE(geometry::annulus_of(two));
  std::vector<Curve> flattened = circle(c, 3.25);
  Curve chord;
  chord.name = "flat";
  chord.a = flattened[3].point(0.0);
  chord.b = flattened[3].point(1.0);
  flattened[3] = chord;
  Domain cut = Domain::from_loops(flattened, {});
  cut.add_hole(geometry::Circle{c, 2.75, "bore"});
  CHECK_FALSE(geometry::annulus_of(cut));
  CHECK_FALSE(geometry::annulus_of(Domain::rectangle({0, 0}, {1, 1})));
}
