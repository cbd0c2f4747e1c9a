#pragma once
// Plane bodies: a polygon (a rectangle is one) minus circular holes, and their boundary as
// named pieces (straight segments and circular arcs) for tractions and penalty constraints.
#include "meshfree/core/types.hpp"
#include <functional>
#include <string>
#include <vector>

namespace mf::geometry {

struct Circle {
  Vec2 center{0.0, 0.0};
  double radius = 0.0;
  std::string name;
};

/// A boundary piece parametrised by t in [0, 1]: a segment from a to b, or an arc of a hole
/// from angle theta0 to theta1. The body lies on the left of a segment (outer boundary
/// counter-clockwise), and outside the circle of an arc.
struct Curve {
  enum class Kind { Segment, Arc };
  Kind kind = Kind::Segment;
  std::string name;
  Vec2 a{0.0, 0.0}, b{0.0, 0.0};
  Vec2 center{0.0, 0.0};
  double radius = 0.0, theta0 = 0.0, theta1 = 0.0;

  Vec2 point(double t) const;
  /// |d point / d t|: the length per unit parameter, constant for both kinds.
  double speed() const;
  double length() const { return speed(); }
  /// Unit normal pointing out of the body.
  Vec2 outward_normal(double t) const;
  /// The piece between parameters t0 < t1, reparametrised to [0, 1].
  Curve piece(double t0, double t1) const;
  /// The distance from p to the nearest point of the curve (its ends included).
  double distance_to(const Vec2& p) const;
  /// The nearest point of the curve to p (its ends included).
  Vec2 closest_point(const Vec2& p) const;
};

class Domain {
public:
  /// Axis-aligned rectangle with edges named bottom, right, top, left.
  static Domain rectangle(const Vec2& origin, const Vec2& size);
  /// Simple polygon; vertices in either orientation. edge_names[i] names the edge from vertex i
  /// to vertex i+1 (default "edge<i>").
  static Domain polygon(std::vector<Vec2> vertices, std::vector<std::string> edge_names = {});

  void add_hole(const Circle& hole);

  /// True for points of the closed body (boundary included within `tol`).
  bool contains(const Vec2& p, double tol = 1e-12) const;
  BoundingBox bounds() const;
  double area_estimate() const;
  const std::vector<Vec2>& vertices() const { return vertices_; }
  const std::vector<std::string>& edge_names() const { return edge_names_; }
  const std::vector<Circle>& holes() const { return holes_; }

  /// The boundary of the body: polygon edges with the parts inside holes removed, and the
  /// parts of hole circles that lie inside the polygon.
  std::vector<Curve> boundary() const;
  /// What a boundary name given by a user selects: the piece or pieces of that name, or, for a
  /// side of the bounding box named by its axis (x_min, x_max, y_min, y_max), the names of the
  /// outline's edges that lie wholly on it (a rectangle's left, right, bottom, top). Empty when
  /// the name selects nothing.
  std::vector<std::string> names_selected(const std::string& name) const;

  /// True for points inside the polygon or within `tol` (relative) of its outline; holes ignored.
  bool within_outline(const Vec2& p, double tol = 1e-12) const;
  /// Distance from p to the polygon outline (not the holes).
  double distance_to_outline(const Vec2& p) const;

private:
  bool inside_polygon(const Vec2& p) const;
  std::vector<Vec2> vertices_; // counter-clockwise
  std::vector<std::string> edge_names_;
  std::vector<Circle> holes_;
  double scale_ = 1.0; // length scale for tolerances
};

/// The signed area of a polygon (positive counter-clockwise), by the shoelace formula.
double signed_area(const std::vector<Vec2>& vertices);

/// Parameter intervals [t0, t1] of `curve` on which `keep` holds, found by sampling and bisection.
std::vector<std::pair<double, double>> kept_intervals(const Curve& curve,
                                                      const std::function<bool(const Vec2&)>& keep);

} // namespace mf::geometry
