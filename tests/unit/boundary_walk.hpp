#pragma once
// The check the plane-body tests make of a boundary: along every piece (at its quarter points
// and, with `ends`, its ends too) the outward normal points out of the body (a step along it
// leaves, one against it stays), the piece lies on the boundary and a point 1e-3 inside it is
// 1e-3 from the boundary. Returns the boundary's length.
#include "meshfree/geometry/domain.hpp"
#include <catch2/catch.hpp>

inline double walk_boundary(const mf::geometry::Domain& d, bool ends = false) {
  double length = 0.0;
  for (const mf::geometry::Curve& piece : d.boundary()) {
    length += piece.length();
    for (const double t : {0.25, 0.5, 0.75}) {
      const mf::Vec2 p = piece.point(t), n = piece.outward_normal(t);
      CHECK(d.contains(p - 1e-6 * n));
      CHECK_FALSE(d.contains(p + 1e-6 * n));
      CHECK(d.distance_to_boundary(p) < 1e-12);
      CHECK(d.distance_to_boundary(p - 1e-3 * n) == Approx(1e-3).margin(1e-12));
    }
    if (ends)
      for (const double t : {0.0, 1.0}) CHECK(d.distance_to_boundary(piece.point(t)) < 1e-12);
  }
  return length;
}
