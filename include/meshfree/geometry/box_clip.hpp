#pragma once
// Plane figures clipped to an axis-aligned box, exactly: a boundary condition's `box` then
// bounds the area it integrates over where its edges fall, not where background cells do.
#include "meshfree/core/types.hpp"
#include <optional>
#include <utility>
#include <vector>

namespace mf::geometry {

/// The parameter interval [t0, t1] of the segment a + t (b - a), t in [0, 1], inside `box`, by
/// the slabs of Liang and Barsky; none if it misses the box or touches it at a point. A segment
/// within `tol` of parallel to a side of the box is inside where it lies within `tol` of it.
std::optional<std::pair<double, double>> clip_segment(const Vec2& a, const Vec2& b,
                                                      const BoundingBox& box, double tol);

/// The simple polygon `vertices` cut to the convex `box` (Sutherland and Hodgman), repeated
/// vertices dropped: exact where the polygon is convex, or where its part inside the box is
/// connected. Fewer than 3 vertices when nothing of positive area is left.
std::vector<Vec2> clip_polygon(const std::vector<Vec2>& vertices, const BoundingBox& box);

} // namespace mf::geometry
