#pragma once
// Plane bodies: a polygon (a rectangle is one) whose corners may be rounded (fillets), minus
// holes (circles, polygons, slots), and their boundary as named pieces (straight segments and
// circular arcs) for tractions and penalty constraints.
#include "meshfree/core/types.hpp"
#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace mf::geometry {

struct Circle {
  Vec2 center{0.0, 0.0};
  double radius = 0.0;
  std::string name;
};

/// A boundary piece parametrised by t in [0, 1]: a segment from a to b, or an arc from angle
/// theta0 to theta1. The body lies on the left of the direction of travel: a segment of the outer
/// boundary runs counter-clockwise, an arc that runs clockwise (a hole's, a rounded inner corner)
/// has the body outside its circle, one that runs counter-clockwise (a rounded outer corner)
/// inside.
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
  /// True where the curve stands between a and b: the segment from a to b passes through it
  /// with both of its ends more than `tol` (a length) off it.
  bool crossed_by(const Vec2& a, const Vec2& b, double tol) const;
};

/// A hole of an outline other than a circle: a polygon (a rectangle is one), a slot, the
/// points within `half_width` of the segment from `a` to `b` (two straight sides and two round
/// ends), or any closed loop of segments and arcs (a hole read from a file). The pieces of a
/// polygon or a slot carry its name, those of a loop their own.
struct OutlineHole {
  enum class Kind { Polygon, Slot, Loop };
  Kind kind = Kind::Polygon;
  std::vector<Vec2> vertices; // a polygon's, counter-clockwise
  Vec2 a{0.0, 0.0}, b{0.0, 0.0};
  double half_width = 0.0;
  std::vector<Curve> curves; // a loop's, clockwise about the hole (the body on their left)
  std::string name;

  /// A polygon hole; vertices in either orientation, a simple polygon of nonzero area.
  static OutlineHole polygon(std::vector<Vec2> vertices, std::string name = {});
  /// A slot from a to b (a == b gives a circle) of width 2 half_width.
  static OutlineHole slot(const Vec2& a, const Vec2& b, double half_width, std::string name = {});
  /// A hole bounded by a closed loop of pieces, in either sense (close_loop); named after its
  /// first piece.
  static OutlineHole loop_of(std::vector<Curve> pieces);
  /// True for points strictly inside the hole, farther than `tol` (absolute) from its outline.
  bool contains(const Vec2& p, double tol = 0.0) const;
  /// The distance from p to the hole's outline.
  double distance_to(const Vec2& p) const;
  /// Its outline as boundary pieces of the body around it: traversed with the body on the left
  /// (clockwise about the hole), named after the hole.
  std::vector<Curve> loop() const;
  BoundingBox bounds() const;
  double area() const;
};

/// A rounded corner of the outline: the arc of `radius` about `center` tangent to the two edges
/// that meet at vertex `vertex`, from `from` on the edge before it to `to` on the edge after.
/// At a convex corner the rounding takes material away, at a re-entrant one it adds it.
struct Fillet {
  std::size_t vertex = 0;
  double radius = 0.0;
  std::string name;
  Vec2 from{0.0, 0.0}, to{0.0, 0.0}, center{0.0, 0.0};
  bool convex = true;

  /// The arc as a boundary piece, named after the fillet, the body on its left.
  Curve arc() const;
  /// True for points between the sharp corner `corner` and the arc: the region the rounding
  /// removes (convex) or adds (re-entrant).
  bool in_cap(const Vec2& corner, const Vec2& p) const;
  /// The area of that region.
  double cap_area(const Vec2& corner) const;
};

class Domain {
public:
  /// Axis-aligned rectangle with edges named bottom, right, top, left.
  static Domain rectangle(const Vec2& origin, const Vec2& size);
  /// Simple polygon; vertices in either orientation. edge_names[i] names the edge from vertex i
  /// to vertex i+1 (default "edge<i>").
  static Domain polygon(std::vector<Vec2> vertices, std::vector<std::string> edge_names = {});
  /// The body inside the closed loop `outline` of named segments and arcs (a body read from a
  /// file), in either sense, minus the loops `holes`. Its vertices are the pieces' starts, so
  /// that an arc's chord is an edge of the polygon, and the arcs' caps (between chord and arc)
  /// are added to it or taken from it.
  static Domain from_loops(std::vector<Curve> outline, std::vector<std::vector<Curve>> holes);

  /// Rounds the corner at vertex `at` (within 1e-9 of the body's size) with an arc of `radius`
  /// tangent to its edges (default name "fillet<k>"). Refused where no vertex is there, the corner
  /// is rounded already or straight, or the arcs' tangent points would not fit on an edge.
  void round_corner(const Vec2& at, double radius, std::string name = {});
  void add_hole(const Circle& hole);
  void add_hole(const OutlineHole& hole);
  /// Adds every hole of `other` (circles and outlines) to this body.
  void add_holes_of(const Domain& other);

  /// True for points of the closed body (boundary included within `tol`).
  bool contains(const Vec2& p, double tol = 1e-12) const;
  BoundingBox bounds() const;
  double area_estimate() const;
  /// The corners of the outline before any rounding; of a body from loops, the pieces' starts.
  const std::vector<Vec2>& vertices() const { return vertices_; }
  /// True where the outline has arcs: rounded corners, or arcs of a body from loops.
  bool has_arcs() const { return !fillets_.empty() || !arcs_.empty(); }
  const std::vector<Fillet>& fillets() const { return fillets_; }
  /// The outline as boundary pieces, counter-clockwise from vertex 0: each edge's straight part
  /// (named as the edge; none where fillets take the whole edge), then the arc of the fillet at
  /// the edge's end, if any. Holes not cut from it.
  const std::vector<Curve>& outline() const { return outline_; }
  const std::vector<std::string>& edge_names() const { return edge_names_; }
  const std::vector<Circle>& holes() const { return holes_; }
  const std::vector<OutlineHole>& outline_holes() const { return outline_holes_; }

  /// The boundary of the body: polygon edges with the parts inside holes removed, and the
  /// parts of hole circles that lie inside the polygon.
  std::vector<Curve> boundary() const;
  /// Curves inside the body where parts of it meet (a geometry file's groups of surfaces), which
  /// a mesh of the body follows; none for the built-in shapes.
  const std::vector<Curve>& interfaces() const { return interfaces_; }
  void set_interfaces(std::vector<Curve> curves) { interfaces_ = std::move(curves); }
  /// What a boundary name given by a user selects: the piece or pieces of that name, or, for a
  /// side of the bounding box named by its axis (x_min, x_max, y_min, y_max), the names of the
  /// outline's edges that lie wholly on it (a rectangle's left, right, bottom, top). Empty when
  /// the name selects nothing.
  std::vector<std::string> names_selected(const std::string& name) const;

  /// True for points inside the outline or within `tol` (relative) of it; holes ignored.
  bool within_outline(const Vec2& p, double tol = 1e-12) const;
  /// Distance from p to the outline (not the holes).
  double distance_to_outline(const Vec2& p) const;
  /// Distance from p to the body's boundary: the outline or a hole's.
  double distance_to_boundary(const Vec2& p) const;
  /// The heights y at which the vertical line through x crosses a hole's outline (circles and
  /// outlines), appended to ys.
  void hole_crossings(double x, std::vector<double>& ys) const;
  /// The heights y at which the vertical line through x crosses the outline, appended to ys.
  void outline_crossings(double x, std::vector<double>& ys) const;

private:
  bool inside_outline(const Vec2& p) const;
  void make_outline();
  std::vector<Vec2> vertices_; // counter-clockwise
  std::vector<std::string> edge_names_;
  std::vector<Fillet> fillets_;
  std::vector<Curve> outline_;
  std::vector<Curve> arcs_; // the arcs of a body from loops, whose caps change the polygon
  std::vector<Circle> holes_;
  std::vector<OutlineHole> outline_holes_;
  std::vector<Curve> interfaces_;
  double scale_ = 1.0; // length scale for tolerances
};

/// Appends the heights at which the vertical line through x crosses curve c.
void vertical_crossings(const Curve& c, double x, std::vector<double>& ys);

/// The loop of pieces in the other sense: their order and each piece reversed (inline: gmsh's
/// reader, outside the library, uses it too).
inline std::vector<Curve> reversed(std::vector<Curve> loop) {
  std::reverse(loop.begin(), loop.end());
  for (Curve& c : loop) {
    std::swap(c.a, c.b);
    std::swap(c.theta0, c.theta1);
  }
  return loop;
}
/// Checks that each piece of `loop` ends where the next starts (within `tol`), the last where the
/// first starts, and that no arc sweeps more than a half turn; returns it counter-clockwise or,
/// with `clockwise`, clockwise.
std::vector<Curve> close_loop(std::vector<Curve> loop, bool clockwise, double tol);
/// The signed area inside a closed loop (positive counter-clockwise): its chords' polygon plus
/// each arc's cap, r^2 (phi - sin phi) / 2 for a sweep of phi, signed by the arc's sense.
double loop_area(const std::vector<Curve>& loop);
/// True for points inside a closed loop: inside its chords' polygon, or else in one arc's cap.
bool inside_loop(const std::vector<Curve>& loop, const Vec2& p);
/// The box around a loop: its pieces' ends and its arcs' extreme points.
BoundingBox loop_bounds(const std::vector<Curve>& loop);

/// True for points inside the polygon (even-odd rule).
bool inside_polygon(const std::vector<Vec2>& vertices, const Vec2& p);

/// The signed area of a polygon (positive counter-clockwise), by the shoelace formula.
double signed_area(const std::vector<Vec2>& vertices);

/// Parameter intervals [t0, t1] of `curve` on which `keep` holds, found by sampling and bisection.
std::vector<std::pair<double, double>> kept_intervals(const Curve& curve,
                                                      const std::function<bool(const Vec2&)>& keep);

} // namespace mf::geometry
