#pragma once
// Integration points where spherical holes (geometry::Sphere) cut a prism:
// - Gauss points of the surface on patches of (w, phi), w along a pole axis and phi the
//   longitude: the area element is r dw dphi ([Archimedes]: a zone's area is 2 pi r times its
//   height), so any Gauss rule integrates the area exactly; patches the body's other boundaries
//   cut are split, then integrated along their Gauss latitudes on the arcs in the body (a plane
//   normal to the pole axis cuts along a latitude: exact);
// - Gauss points of a background cell the sphere touches: the cell split into eight down to the
//   cut levels, and a finest cell the surface cuts integrated along lines in the axis nearest the
//   sphere's normal there, each line's part outside the ball found in closed form.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <vector>

namespace mf::implicit {

/// Gauss points (`order` a direction) of the part of `s`'s surface in the body, on patches about
/// `part` long; patches the body's other faces cut split `cut_levels` times. The pole axis is z
/// unless only the body's faces normal to x or y cut the sphere off its centre. Normals point out
/// of the body (into the sphere).
SolidPoints sphere_face_points(const geometry::Prism& body, const geometry::Sphere& s, double part,
                               int order, int cut_levels);

/// True when some sphere of the body meets the open box (lo, hi).
bool sphere_touches(const geometry::Prism& body, const Vec3& lo, const Vec3& hi);

/// Appends the Gauss points of the body in the box (lo, hi), a background cell some sphere
/// touches: split into eight while larger than `sizing` asks, then `cut_levels` times where a
/// sphere's surface cuts it.
void sphere_cell_points(const geometry::Prism& body, const Vec3& lo, const Vec3& hi, int order,
                        int cut_levels, const quadrature::CellSizing& sizing, SolidPoints& out);

} // namespace mf::implicit
