// The names a user gives a body's boundary: a piece's own name, or a side of the bounding box
// by its axis (x_min .. z_max), which cannot be misread as "bottom" can (y here, z to many).
// Over a rectangle, an L-shaped polygon, a polygon with two edges on one side, a user's own edge
// named like a side, a hole, a prism's ends, and problem files whose conditions name the sides.
#include "meshfree/geometry/prism.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>

using namespace mf;
using Names = std::vector<std::string>;

TEST_CASE("an axis side names the outline's edges that lie wholly on it", "[geometry][names]") {
  geometry::Domain rect = geometry::Domain::rectangle({1.0, -2.0}, {3.0, 0.5});
  rect.add_hole({{2.5, -1.75}, 0.1, "hole"});
  CHECK(rect.names_selected("x_min") == Names{"left"});
  CHECK(rect.names_selected("x_max") == Names{"right"});
  CHECK(rect.names_selected("y_min") == Names{"bottom"});
  CHECK(rect.names_selected("y_max") == Names{"top"});
  CHECK(rect.names_selected("top") == Names{"top"});
  CHECK(rect.names_selected("hole") == Names{"hole"});
  CHECK(rect.names_selected("z_min").empty()); // a plane body has no z side
  CHECK(rect.names_selected("north").empty());

  // An L: two of its six edges lie inside the bounding box.
  const geometry::Domain l = geometry::Domain::polygon(
      {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {"a", "b", "c", "d", "e", "f"});
  CHECK(l.names_selected("y_min") == Names{"a"});
  CHECK(l.names_selected("x_max") == Names{"b"});
  CHECK(l.names_selected("y_max") == Names{"e"});
  CHECK(l.names_selected("x_min") == Names{"f"});

  // Two edges on x = 0, given in clockwise order (the polygon is turned, its names kept).
  const geometry::Domain two = geometry::Domain::polygon({{0, 0}, {0, 0.5}, {0, 1}, {1, 1}, {1, 0}},
                                                         {"p", "q", "top", "right", "bottom"});
  CHECK(two.names_selected("x_min") == Names{"q", "p"});
  CHECK(two.names_selected("y_min") == Names{"bottom"});

  // A user's edge named like a side keeps its own meaning.
  const geometry::Domain own = geometry::Domain::polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}},
                                                         {"x_min", "right", "top", "left"});
  CHECK(own.names_selected("x_min") == Names{"x_min"});

  geometry::Prism prism;
  prism.section = geometry::Domain::rectangle({0, 0}, {2, 1});
  CHECK(prism.names_selected("z_min") == Names{"back"});
  CHECK(prism.names_selected("z_max") == Names{"front"});
  CHECK(prism.names_selected("x_max") == Names{"right"});
  CHECK(prism.names_selected("front") == Names{"front"});
  CHECK(prism.names_selected("up").empty());
}

TEST_CASE("conditions on axis sides read as the conditions on the sides' own names",
          "[geometry][names][spec]") {
  const spec::ProblemSpec block = load_problem(
      "block_uniaxial_3d", {"boundary.0.faces=x_min", "boundary.1.faces=[y_min]",
                            "boundary.2.faces=z_min", "boundary.3.faces=[z_max, front]"});
  const Names faces[4] = {{"left"}, {"bottom"}, {"back"}, {"front"}};
  for (int k = 0; k < 4; ++k) CHECK(block.solid().boundary[k].faces == faces[k]);
  const spec::ProblemSpec plate = load_problem("plate_tension", {"boundary.1.edges=y_max"});
  CHECK(plate.galerkin().boundary[1].on.edges == Names{"y_max"});
  // Read as the top edge: the same length and the same points as `top`.
  const spec::ProblemSpec top = load_problem("plate_tension");
  const auto a = spec::select_boundary(plate.domain, plate.galerkin().boundary[1].on, "b");
  const auto b = spec::select_boundary(top.domain, top.galerkin().boundary[1].on, "b");
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    CHECK(a[k].name == "top");
    CHECK(a[k].a == b[k].a);
    CHECK(a[k].b == b[k].b);
  }
  CHECK_THROWS_WITH(load_problem("block_uniaxial_3d", {"boundary.0.faces=w_min"}),
                    Catch::Contains("boundary[0].faces: no face is named 'w_min'"));
}
