#pragma once
// Integration over a background cell cut by a circular hole on the exact region, the cell minus
// the disc: no sub-cell sampling, no staircase along the arc.
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/core/types.hpp"
#include <vector>

namespace mf::quadrature {

/// Appends Gauss points and area weights covering box \ disc(center, radius).
///
/// The region is split into pieces by the rays from the centre through the box's corners and
/// through the points where the circle crosses the box's edges. Between two such rays the
/// region lies between one straight outer edge and, inside, either the arc or another edge of
/// the box. Each piece is mapped from the unit square by x(s, t) = P(s) + t (Q(s) - P(s)), with
/// Q(s) running linearly along the outer edge and P(s) its radial projection onto the circle
/// (the arc, exactly) or its partner on the inner edge (then the map is bilinear, exact for
/// polynomials). `rule` is applied in s and t; pieces wider than 45 degrees are split.
/// On a unit square minus a quarter disc of radius 1/2, 3 x 3 points per piece integrate the
/// area to 4e-5 and x^2 y to 6e-6 (relative), 5 x 5 to 1e-9 and 1e-7.
void cell_minus_disc(const BoundingBox& box, const Vec2& center, double radius,
                     const GaussRule& rule, std::vector<Vec2>& x, std::vector<double>& weight);

/// True when the segment from a to b passes through the interior of `box` shrunk by `tol`.
bool segment_crosses_interior(const BoundingBox& box, const Vec2& a, const Vec2& b, double tol);

} // namespace mf::quadrature
