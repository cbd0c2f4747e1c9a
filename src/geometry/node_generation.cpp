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

std::vector<Curve> split_at_refinements(const Curve& c,
                                        const std::vector<Refinement>& refinements) {
  std::vector<double> cuts{0.0, 1.0};
  for (const auto& r : refinements)
    for (const auto& [t0, t1] :
         kept_intervals(c, [&](const Vec2& p) { return r.box.contains(p); })) {
      cuts.push_back(t0);
      cuts.push_back(t1);
    }
  std::sort(cuts.begin(), cuts.end());
  std::vector<Curve> parts;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i + 1] - cuts[i] > 1e-12) parts.push_back(c.piece(cuts[i], cuts[i + 1]));
  return parts;
}

namespace {

/// Appends lattice points of spacing h anchored at `anchor`, restricted to `box`, that `keep`.
template <class Keep>
void add_lattice(const Vec2& anchor, double h, const BoundingBox& box, Keep&& keep,
                 std::vector<Vec2>& out, std::vector<double>& out_h) {
  const double eps = 1e-9 * h;
  const long i0 = static_cast<long>(std::ceil((box.lo.x() - anchor.x() - eps) / h));
  const long i1 = static_cast<long>(std::floor((box.hi.x() - anchor.x() + eps) / h));
  const long j0 = static_cast<long>(std::ceil((box.lo.y() - anchor.y() - eps) / h));
  const long j1 = static_cast<long>(std::floor((box.hi.y() - anchor.y() + eps) / h));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const Vec2 p = anchor + Vec2(static_cast<double>(i) * h, static_cast<double>(j) * h);
      if (keep(p)) {
        out.push_back(p);
        out_h.push_back(h);
      }
    }
}

} // namespace

NodeCloud generate_nodes(const Domain& domain, double spacing,
                         const std::vector<Refinement>& refinements) {
  MF_REQUIRE(spacing > 0.0, "node spacing must be positive, got ", spacing);
  const BoundingBox bb = domain.bounds();
  const double estimate = domain.area_estimate() / (spacing * spacing);
  MF_REQUIRE(estimate < 5e7, "node spacing ", spacing, " would create about ", estimate,
             " nodes; that is more than this code is meant to handle in one run");

  // 1. Boundary nodes: each piece divided evenly at about the local spacing.
  std::vector<Vec2> bnd;
  std::vector<double> bnd_h;
  for (const Curve& whole : domain.boundary())
    for (const Curve& c : split_at_refinements(whole, refinements)) {
      const double h = local_spacing(c.point(0.5), spacing, refinements);
      const int n = std::max(1, static_cast<int>(std::ceil(c.length() / h - 1e-9)));
      for (int k = 0; k <= n; ++k) {
        bnd.push_back(c.point(static_cast<double>(k) / n));
        bnd_h.push_back(h);
      }
    }

  // 2. Interior lattice: base spacing outside refinement boxes, fine spacing inside them.
  std::vector<Vec2> lat;
  std::vector<double> lat_h;
  auto in_any_box = [&](const Vec2& p) {
    for (const auto& r : refinements)
      if (r.box.contains(p, -1e-9 * spacing)) return true;
    return false;
  };
  add_lattice(
      bb.lo, spacing, bb, [&](const Vec2& p) { return domain.contains(p) && !in_any_box(p); }, lat,
      lat_h);
  for (const auto& r : refinements) {
    MF_REQUIRE(r.spacing > 0.0, "refinement spacing must be positive, got ", r.spacing);
    add_lattice(
        bb.lo, r.spacing, r.box,
        [&](const Vec2& p) {
          return domain.contains(p) && local_spacing(p, spacing, refinements) == r.spacing;
        },
        lat, lat_h);
  }

  // 3. Merge: boundary nodes first (deduplicated among themselves), then lattice nodes that
  // are not too close to an accepted node.
  NodeCloud cloud;
  std::vector<Vec2> all = bnd;
  all.insert(all.end(), lat.begin(), lat.end());
  std::vector<double> all_h = bnd_h;
  all_h.insert(all_h.end(), lat_h.begin(), lat_h.end());
  const neighbors::PointGrid grid(all, spacing);
  std::vector<char> accepted(all.size(), 0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const double min_gap = (i < bnd.size() ? 1e-6 : 0.45) * all_h[i];
    bool clash = false;
    grid.for_each_within(all[i], min_gap, [&](int j) {
      if (accepted[j]) clash = true;
    });
    if (clash) continue;
    accepted[i] = 1;
  }
  std::vector<int> order;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (accepted[i]) order.push_back(static_cast<int>(i));

  // 4. Strip ordering: rows of height `spacing`, x increasing within a row.
  auto key = [&](int i) {
    const double row = std::floor((all[i].y() - bb.lo.y()) / spacing + 0.5);
    return std::make_pair(row, all[i].x());
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ka = key(a), kb = key(b);
    if (ka != kb) return ka < kb;
    return all[a].y() < all[b].y();
  });
  for (int i : order) {
    cloud.x.push_back(all[i]);
    cloud.spacing.push_back(all_h[i]);
    cloud.volume.push_back(all_h[i] * all_h[i]);
  }
  return cloud;
}

} // namespace mf::geometry
