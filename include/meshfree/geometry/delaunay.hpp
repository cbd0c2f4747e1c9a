#pragma once
// Triangles through a set of plane points: the Delaunay triangulation of the points, and the
// part of it that lies in a body (a display mesh through the nodes of a meshfree cloud, with no
// mesher to load).
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include <array>
#include <vector>

namespace mf::geometry {

using Triangle = std::array<int, 3>;

/// The Delaunay triangulation of distinct points x (at least three, not all on one line),
/// counter-clockwise, by incremental insertion and edge flips (Lawson 1977; Guibas & Stolfi
/// 1985). Degenerate inputs (a lattice's four points on one circle, three on one line) are
/// resolved by moving each point by a billionth of the set's size in a fixed pseudo-random
/// direction for the tests only, so that the result is one triangulation of the points as given;
/// triangles of no area (collinear points) are left out. Empty if the walk to a point or the
/// flips do not end (not seen: bounds of four walk steps a triangle and 100 flips a point).
std::vector<Triangle> delaunay(const std::vector<Vec2>& x);

/// The triangles of delaunay(x) whose centroid lies in `domain`, for points x of the body that
/// include points along all of its boundary (a meshfree cloud's nodes). Along a hole their edges
/// are chords of its circle; elsewhere they follow the boundary. Empty where some kept triangle
/// leaves the body other than along a chord of a hole between two points on its circle (its
/// edges sampled at a quarter, a half and three quarters): points too sparse along the boundary
/// for their triangulation to follow it.
std::vector<Triangle> body_triangles(const Domain& domain, const std::vector<Vec2>& x);

} // namespace mf::geometry
