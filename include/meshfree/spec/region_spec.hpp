#pragma once
// The shapes a problem file names: points, boxes, circles, rings and the regions built from them
// (boundary selection, material regions, initial conditions, loads), gauges and blasts. One set
// of types for every analysis, in 1, 2 and 3 dimensions: unused coordinates of a point are 0 and
// unused axes of a box are unbounded.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/domain.hpp"
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mf::spec {

using Point = Eigen::Vector3d;

struct Box {
  Point lo{0, 0, 0}, hi{0, 0, 0};
  bool contains(const Point& p, double tol) const {
    return (p - lo).minCoeff() >= -tol && (hi - p).minCoeff() >= -tol;
  }
};

/// A disc in the x-y plane (a cylinder along z in 3D).
struct Circle {
  Point center{0, 0, 0};
  double radius = 0.0;
};

/// The annulus between two radii about a centre in the x-y plane.
struct Ring {
  Point center{0, 0, 0};
  double inner_radius = 0.0, outer_radius = 0.0;
};

/// A part of space or of a body's boundary: a box, a circle (only what lies inside it is kept),
/// a ring, holes (circles, or polygons and slots: what lies inside them is left out; cylinders
/// and prisms along z in 3D), and named boundary pieces of a 2D body. An empty region is
/// everything.
struct Region {
  std::optional<Box> box;
  std::optional<Circle> circle;
  std::optional<Ring> ring;
  std::vector<Circle> holes;
  std::vector<geometry::OutlineHole> outline_holes;
  std::vector<std::string> edges;
  // A part of a geometry file's body (a physical group of its surfaces): its points, and those
  // within tol of its boundary.
  std::optional<geometry::Domain> part;

  bool everything() const {
    return !box && !circle && !ring && holes.empty() && outline_holes.empty() && edges.empty() &&
           !part;
  }
  bool contains(const Point& p, double tol) const {
    if (box && !box->contains(p, tol)) return false;
    if (part && !part->contains(Vec2(p.x(), p.y()), 0.0) &&
        part->distance_to_boundary(Vec2(p.x(), p.y())) > tol)
      return false;
    const auto r2 = [&p](const Point& c) {
      const double dx = p.x() - c.x(), dy = p.y() - c.y();
      return dx * dx + dy * dy;
    };
    if (circle && r2(circle->center) > circle->radius * circle->radius) return false;
    for (const Circle& h : holes)
      if (r2(h.center) < h.radius * h.radius) return false;
    for (const geometry::OutlineHole& h : outline_holes)
      if (h.contains(Vec2(p.x(), p.y()))) return false;
    if (ring) {
      const double d2 = r2(ring->center);
      if (d2 < ring->inner_radius * ring->inner_radius ||
          d2 > ring->outer_radius * ring->outer_radius)
        return false;
    }
    return true;
  }
};

/// A point whose history is recorded (the nearest particle, or the field at the point).
struct GaugeSpec {
  std::string name;
  Point at{0, 0, 0};
};

/// time: the end of an explicit run and what sets its step (peridynamics: a safety factor on
/// the stable step, or a given dt; SPH: the Courant number).
struct TimeSpec {
  double end = 0.0;
  double dt = 0.0; // 0: from the stability bound
  double safety = 0.8;
  double courant = 0.3;
};

/// When an explicit run writes checkpoints (output.checkpoint_interval of simulated time,
/// output.checkpoint_wall_interval seconds of wall time; io/checkpoint.hpp).
struct CheckpointPolicy {
  double interval = 0.0;        // of simulated time; 0: none on the simulated clock
  double wall_interval = 600.0; // seconds of wall time; 0: none on the wall clock
  bool any() const { return interval > 0.0 || wall_interval > 0.0; }
};

/// The problem as run, one "key.path = value" per scalar of the file after --set (what a restart
/// compares with its checkpoint's).
using ProblemSettings = std::vector<std::pair<std::string, std::string>>;

/// output of an explicit run: the intervals of the history and field series, the gauges and the
/// checkpoints.
struct SeriesOutputSpec {
  double history_interval = 0.0, fields_interval = 0.0; // 0: every step / start and end only
  std::vector<GaugeSpec> gauges;
  CheckpointPolicy checkpoint;
};

/// A TNT charge whose air blast loads a face (Kingery-Bulmash, loads/blast.hpp).
struct BlastSpec {
  double tnt_mass = 0.0;          // kg of TNT (equivalent)
  bool surface_burst = true;      // hemispherical surface burst, else spherical free air
  bool clamp_below_range = false; // closer than the fits reach: the values at their nearest end
  Point charge{0, 0, 0};          // the charge's centre
  Point normal{0, 0, 0};          // unit outward normal of the loaded face
};

} // namespace mf::spec
