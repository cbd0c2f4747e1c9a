#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace mf::geometry {

double local_spacing(const Vec2& p, double spacing, const std::vector<Refinement>& refinements) {
  double h = spacing;
  for (const auto& r : refinements)
    if (r.box.contains(p, 1e-12 * spacing)) h = std::min(h, r.spacing);
  return h;
}

namespace {

/// The parameters where c enters or leaves a refinement box, with 0 and 1, sorted.
std::vector<double> refinement_cuts(const Curve& c, const std::vector<Refinement>& refinements) {
  std::vector<double> cuts{0.0, 1.0};
  for (const auto& r : refinements)
    for (const auto& [t0, t1] :
         kept_intervals(c, [&](const Vec2& p) { return r.box.contains(p); })) {
      cuts.push_back(t0);
      cuts.push_back(t1);
    }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

/// The pieces of c between consecutive cuts.
std::vector<Curve> pieces_between(const Curve& c, const std::vector<double>& cuts) {
  std::vector<Curve> parts;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i + 1] - cuts[i] > 1e-12) parts.push_back(c.piece(cuts[i], cuts[i + 1]));
  return parts;
}

} // namespace

std::vector<Curve> split_at_refinements(const Curve& c,
                                        const std::vector<Refinement>& refinements) {
  return pieces_between(c, refinement_cuts(c, refinements));
}

namespace {

/// Lattice nodes nearer than this fraction of their spacing to the boundary are dropped: a row
/// a sliver from an edge (a spacing that does not divide the body, a row grazing a hole between
/// two boundary nodes) makes nearly dependent shape functions, on which multigrid stalls.
constexpr double kBoundaryGap = 0.3;

/// Steps of a lattice that fits the interval [0, L] in each direction: round(L / h) intervals,
/// so that the first and last rows land on the box's edges. Where h divides L (to 1e-9) the
/// step is h itself, so that such lattices keep their exact coordinates.
Vec2 fitted_steps(const Vec2& size, double h) {
  Vec2 step;
  for (int d = 0; d < 2; ++d) {
    const double n = std::max(1.0, std::round(size[d] / h));
    step[d] = std::abs(size[d] / h - n) <= 1e-9 * n ? h : size[d] / n;
  }
  return step;
}

/// Intervals of boundary piece c at spacing h: with the steps of a fitted lattice (`step`, null
/// for none), round(L / step) along a segment parallel to an axis (the lattice's count over that
/// length); ceil(L / h) otherwise.
int boundary_intervals(const Curve& c, double h, const Vec2* step) {
  if (step && c.kind == Curve::Kind::Segment) {
    const Vec2 d = c.b - c.a;
    for (int axis = 0; axis < 2; ++axis)
      if (d[1 - axis] == 0.0)
        return static_cast<int>(std::round(std::abs(d[axis]) / (*step)[axis]));
  }
  return static_cast<int>(std::ceil(c.length() / h - 1e-9));
}

/// Appends the points of the lattice anchor + (i step.x, j step.y) inside `box` that `keep`;
/// each gets the nominal spacing h.
template <class Keep>
void add_lattice(const Vec2& anchor, const Vec2& step, const BoundingBox& box, double h,
                 Keep&& keep, std::vector<Vec2>& out, std::vector<double>& out_h) {
  // Rows within a billionth of a step of the box's edges belong to it (the step, not h: a
  // spacing larger than the body is fitted to one interval).
  const double ex = 1e-9 * step.x(), ey = 1e-9 * step.y();
  const long i0 = static_cast<long>(std::ceil((box.lo.x() - anchor.x() - ex) / step.x()));
  const long i1 = static_cast<long>(std::floor((box.hi.x() - anchor.x() + ex) / step.x()));
  const long j0 = static_cast<long>(std::ceil((box.lo.y() - anchor.y() - ey) / step.y()));
  const long j1 = static_cast<long>(std::floor((box.hi.y() - anchor.y() + ey) / step.y()));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const Vec2 p =
          anchor + Vec2(static_cast<double>(i) * step.x(), static_cast<double>(j) * step.y());
      if (keep(p)) {
        out.push_back(p);
        out_h.push_back(h);
      }
    }
}

/// True if p is a point of the lattice anchor + h Z^2 (to 1e-9 of h).
bool on_lattice(const Vec2& p, const Vec2& anchor, double h) {
  for (int d = 0; d < 2; ++d) {
    const double k = (p[d] - anchor[d]) / h;
    if (std::abs(k - std::round(k)) > 1e-9) return false;
  }
  return true;
}

/// True where p lies inside the union of the boxes finer than h: each of the four points a
/// quarter of `finest` from p diagonally lies in one of them.
bool inside_finer_union(const Vec2& p, double h, double finest,
                        const std::vector<Refinement>& refinements) {
  for (const Vec2& dir : {Vec2(1, 1), Vec2(1, -1), Vec2(-1, 1), Vec2(-1, -1)}) {
    const Vec2 q = p + 0.25 * finest * dir;
    if (std::none_of(refinements.begin(), refinements.end(),
                     [&](const Refinement& r) { return r.spacing < h && r.box.contains(q); }))
      return false;
  }
  return true;
}

/// True where a lattice of spacing h gives way to a finer refinement box: inside the box, or
/// outside it by less than half the box's spacing (such a row would lie a sliver from the box's
/// outer row), unless p is also a node of the box's lattice (anchored at `anchor`) on its
/// border, where the merge keeps one of the two. A point on the borders of several finer boxes
/// but inside their union (where overlapping boxes meet) gives way too: kept, its coarse
/// support would reach across the finer nodes around it.
bool yields_to_finer_box(const Vec2& p, double h, const Vec2& anchor,
                         const std::vector<Refinement>& refinements) {
  double finest = h;
  for (const auto& r : refinements) {
    if (r.spacing >= h || !r.box.contains(p, 0.5 * r.spacing)) continue;
    const double tol = 1e-9 * h;
    const bool on_border = r.box.contains(p, tol) && !r.box.contains(p, -tol);
    if (!(on_border && on_lattice(p, anchor, r.spacing))) return true;
    finest = std::min(finest, r.spacing);
  }
  return finest < h && inside_finer_union(p, h, finest, refinements);
}

/// Node positions and the spacing each was placed at.
struct PlacedNodes {
  std::vector<Vec2> x;
  std::vector<double> h;
};

/// Boundary pieces are not cut nearer than this fraction of the local spacing to each other.
constexpr double kShortestPiece = 0.5;

/// The cuts of a boundary curve at the boxes' borders, less those nearer than kShortestPiece of
/// the local spacing (the finer at either end) to the cut kept before them or to the curve's
/// end. Each cut is a boundary node, and the borders of many boxes (adapted clouds put boxes
/// round boundary nodes anywhere) cross an edge at points arbitrarily close together: two nodes
/// a sliver apart have nearly the same shape function, so that their parameters oscillate and
/// multigrid stalls.
std::vector<double> node_cuts(const Curve& c, double spacing,
                              const std::vector<Refinement>& refinements) {
  const std::vector<double> cuts = refinement_cuts(c, refinements);
  const auto h_at = [&](double t) { return local_spacing(c.point(t), spacing, refinements); };
  const double length = c.length(), h_end = h_at(1.0);
  std::vector<double> kept{0.0};
  double h_kept = h_at(0.0); // the local spacing at the last cut kept
  for (std::size_t i = 1; i + 1 < cuts.size(); ++i) {
    const double t = cuts[i], h = h_at(t);
    if ((t - kept.back()) * length >= kShortestPiece * std::min(h, h_kept) &&
        (1.0 - t) * length >= kShortestPiece * std::min(h, h_end))
      kept.push_back(t), h_kept = h;
  }
  kept.push_back(1.0);
  return kept;
}

/// Boundary nodes: each piece divided evenly at about the local spacing. An axis-parallel
/// segment at the base spacing takes as many intervals as the base lattice over its length, so
/// that a side of the bounding box holds the lattice's rows; other pieces ceil(L / h).
PlacedNodes boundary_nodes(const Domain& domain, double spacing, const Vec2& base_step,
                           const std::vector<Refinement>& refinements) {
  PlacedNodes bnd;
  for (const Curve& whole : domain.boundary())
    for (const Curve& c : pieces_between(whole, node_cuts(whole, spacing, refinements))) {
      const double h = local_spacing(c.point(0.5), spacing, refinements);
      const int n = std::max(1, boundary_intervals(c, h, h == spacing ? &base_step : nullptr));
      for (int k = 0; k <= n; ++k) {
        bnd.x.push_back(c.point(static_cast<double>(k) / n));
        bnd.h.push_back(h);
      }
    }
  return bnd;
}

/// True if a lattice of steps `step` from `anchor`, laid over `extent`, has a row along axis d
/// strictly between a and b.
bool has_row_between(double a, double b, int d, const Vec2& anchor, const Vec2& step,
                     const BoundingBox& extent) {
  const double lo = std::max(a, extent.lo[d]), hi = std::min(b, extent.hi[d]);
  const double tol = 1e-9 * step[d];
  const double first = std::floor((lo - anchor[d]) / step[d] + 1e-9) + 1.0;
  return lo < hi && anchor[d] + first * step[d] < hi - tol;
}

/// True if a lattice of steps `step` from `anchor` has a row along axis d at a.
bool on_row(double a, int d, const Vec2& anchor, const Vec2& step) {
  const double k = (a - anchor[d]) / step[d];
  return std::abs(k - std::round(k)) <= 1e-9;
}

/// The boxes over which the refinement lattices are laid: each box as given, but taken on to the
/// body's bounding edge on a side where no row of a coarser lattice can stand between it and that
/// edge (clear of the box by half its spacing, of the edge by kBoundaryGap of its own; or on the
/// box's side, where both lattices have a row, a whole coarser spacing from the edge). Left
/// there, the strip beyond the box's outer row would hold the boundary's own nodes alone, a line
/// on which a linear basis is undefined wherever the box's supports do not reach.
std::vector<Refinement> lattice_extents(const BoundingBox& bb, double spacing,
                                        const Vec2& base_step,
                                        const std::vector<Refinement>& refinements) {
  std::vector<Refinement> out = refinements;
  for (Refinement& r : out)
    for (int d = 0; d < 2; ++d)
      for (const bool upper : {false, true}) {
        const double edge = upper ? bb.hi[d] : bb.lo[d];
        const double side = upper ? r.box.hi[d] : r.box.lo[d];
        const double sign = upper ? 1.0 : -1.0;
        if (sign * (edge - side) <= 0.0) continue;
        const auto coarser_row = [&](const Vec2& step, double h, const BoundingBox& extent) {
          const double near = side + sign * 0.5 * r.spacing, far = edge - sign * kBoundaryGap * h;
          if (has_row_between(std::min(near, far), std::max(near, far), d, bb.lo, step, extent))
            return true;
          // or a row of both lattices on the side, a whole cell from the edge
          const double tol = 1e-9 * h;
          return side >= extent.lo[d] - tol && side <= extent.hi[d] + tol &&
                 on_row(side, d, bb.lo, step) &&
                 on_row(side, d, bb.lo, Vec2::Constant(r.spacing)) &&
                 sign * (edge - side) >= step[d] - tol;
        };
        bool row = coarser_row(base_step, spacing, bb);
        for (const Refinement& m : refinements)
          if (m.spacing > r.spacing)
            row = row || coarser_row(Vec2(m.spacing, m.spacing), m.spacing, m.box);
        if (!row) (upper ? r.box.hi[d] : r.box.lo[d]) = edge;
      }
  return out;
}

/// Interior lattices: the base spacing fitted to the bounding box, so that its first and last
/// rows land on the edges; each refinement box the lattice of its spacing from the same corner,
/// laid over its `lattice_extents`. Nodes a sliver from the boundary or from a finer box are
/// left out.
PlacedNodes lattice_nodes(const Domain& domain, double spacing, const Vec2& base_step,
                          const std::vector<Refinement>& given) {
  const BoundingBox bb = domain.bounds();
  const std::vector<Refinement> refinements = lattice_extents(bb, spacing, base_step, given);
  PlacedNodes lat;
  auto clear_of_boundary = [&](const Vec2& p, double h) {
    return domain.contains(p) && domain.distance_to_boundary(p) >= kBoundaryGap * h;
  };
  add_lattice(
      bb.lo, base_step, bb, spacing,
      [&](const Vec2& p) {
        return clear_of_boundary(p, spacing) &&
               !yields_to_finer_box(p, spacing, bb.lo, refinements);
      },
      lat.x, lat.h);
  for (const auto& r : refinements) {
    MF_REQUIRE(r.spacing > 0.0, "refinement spacing must be positive, got ", r.spacing);
    add_lattice(
        bb.lo, Vec2(r.spacing, r.spacing), r.box, r.spacing,
        [&](const Vec2& p) {
          return clear_of_boundary(p, r.spacing) &&
                 local_spacing(p, spacing, refinements) == r.spacing &&
                 !yields_to_finer_box(p, r.spacing, bb.lo, refinements);
        },
        lat.x, lat.h);
  }
  return lat;
}

/// Merge: the first `boundary` nodes (deduplicated among themselves), then the others that are
/// not too close to an accepted node; returns the indices of the accepted ones.
std::vector<int> accept_nodes(const PlacedNodes& all, std::size_t boundary, double spacing) {
  const neighbors::PointGrid grid(all.x, spacing);
  std::vector<char> accepted(all.x.size(), 0);
  for (std::size_t i = 0; i < all.x.size(); ++i) {
    const double min_gap = (i < boundary ? 1e-6 : 0.45) * all.h[i];
    bool clash = false;
    grid.for_each_within(all.x[i], min_gap, [&](int j) {
      if (accepted[j]) clash = true;
    });
    if (clash) continue;
    accepted[i] = 1;
  }
  std::vector<int> order;
  for (std::size_t i = 0; i < all.x.size(); ++i)
    if (accepted[i]) order.push_back(static_cast<int>(i));
  return order;
}

/// Strip ordering: rows of height `spacing` from `lo`, x increasing within a row.
void sort_in_strips(const std::vector<Vec2>& x, const Vec2& lo, double spacing,
                    std::vector<int>& order) {
  auto key = [&](int i) {
    const double row = std::floor((x[i].y() - lo.y()) / spacing + 0.5);
    return std::make_pair(row, x[i].x());
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ka = key(a), kb = key(b);
    if (ka != kb) return ka < kb;
    return x[a].y() < x[b].y();
  });
}

} // namespace

NodeCloud generate_nodes(const Domain& domain, double spacing,
                         const std::vector<Refinement>& refinements) {
  MF_REQUIRE(spacing > 0.0, "node spacing must be positive, got ", spacing);
  const BoundingBox bb = domain.bounds();
  const double estimate = domain.area_estimate() / (spacing * spacing);
  MF_REQUIRE(estimate < 5e7, "node spacing ", spacing, " would create about ", estimate,
             " nodes; that is more than this code is meant to handle in one run");
  const Vec2 base_step = fitted_steps(bb.size(), spacing);
  PlacedNodes all = boundary_nodes(domain, spacing, base_step, refinements);
  const std::size_t boundary = all.x.size();
  const PlacedNodes lat = lattice_nodes(domain, spacing, base_step, refinements);
  all.x.insert(all.x.end(), lat.x.begin(), lat.x.end());
  all.h.insert(all.h.end(), lat.h.begin(), lat.h.end());
  std::vector<int> order = accept_nodes(all, boundary, spacing);
  sort_in_strips(all.x, bb.lo, spacing, order);
  NodeCloud cloud;
  for (int i : order) {
    cloud.x.push_back(all.x[i]);
    cloud.spacing.push_back(all.h[i]);
    cloud.volume.push_back(all.h[i] * all.h[i]);
  }
  return cloud;
}

void grade_spacing(NodeCloud& cloud) {
  if (cloud.x.empty()) return;
  const double largest = *std::max_element(cloud.spacing.begin(), cloud.spacing.end());
  const neighbors::PointGrid grid(cloud.x, largest);
  const std::vector<double> nominal = cloud.spacing;
  for (std::size_t i = 0; i < cloud.x.size(); ++i)
    grid.for_each_within(cloud.x[i], largest * (1.0 + 1e-9), [&](int j) {
      if (nominal[j] > cloud.spacing[i] &&
          (cloud.x[i] - cloud.x[j]).norm() <= nominal[j] * (1.0 + 1e-9))
        cloud.spacing[i] = nominal[j];
    });
}

} // namespace mf::geometry
