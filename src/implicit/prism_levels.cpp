#include "meshfree/implicit/prism_levels.hpp"
#include <algorithm>
#include <cmath>
#include <optional>

namespace mf::implicit {

namespace {

/// Equal layers of [origin, origin + length]: round(length / spacing), at least one.
Levels equal_layers(double origin, double length, double spacing) {
  const int n = std::max(1, static_cast<int>(std::lround(length / spacing)));
  Levels l;
  l.spacing = spacing;
  const double step = length / n;
  for (int k = 0; k <= n; ++k) l.at.push_back({origin, step, k});
  return l;
}

/// The box's z range widened by `margin`, clipped to the body and widened again to the base
/// levels that enclose it (at least one base layer); none when it misses the body.
std::optional<std::pair<double, double>>
snapped_range(const Levels& base, const geometry::Refinement& r, double margin, double tol) {
  const double z0 = base.at.front().z(), z1 = base.at.back().z();
  const double lo = std::max(r.z_lo - margin, z0), hi = std::min(r.z_hi + margin, z1);
  if (hi < lo - tol) return std::nullopt;
  const Level& l = base.at.front();
  const int n = static_cast<int>(base.at.size()) - 1;
  int k0 = std::clamp(static_cast<int>(std::floor((lo - z0) / l.step + 1e-9)), 0, n);
  int k1 = std::clamp(static_cast<int>(std::ceil((hi - z0) / l.step - 1e-9)), 0, n);
  if (k1 <= k0) { // a range of no thickness: the base layer above it (below it at the top)
    k1 = std::min(k0 + 1, n);
    k0 = k1 - 1;
  }
  return std::make_pair(base.at[k0].z(), base.at[k1].z());
}

} // namespace

std::vector<Levels> prism_levels(const geometry::Prism& body, double spacing,
                                 const std::vector<geometry::Refinement>& refinement, double scale,
                                 double reach) {
  const double tol = 1e-9 * body.size();
  std::vector<Levels> grids{equal_layers(body.z0, body.depth, spacing)};
  for (const geometry::Refinement& r : refinement) {
    const double s = r.spacing * scale;
    if (!r.along_z)
      grids.push_back(Levels{s, {}});
    else if (const auto range = snapped_range(grids.front(), r, reach * r.spacing, tol))
      grids.push_back(equal_layers(range->first, range->second - range->first, s));
    else
      grids.push_back(Levels{s, {}});
  }
  return grids;
}

std::vector<geometry::Refinement> boxes_of(const std::vector<int>& boxes,
                                           const std::vector<geometry::Refinement>& refinement) {
  std::vector<geometry::Refinement> out;
  for (int i : boxes) out.push_back(refinement[i]);
  return out;
}

std::vector<MergedLevel> merged_levels(const std::vector<Levels>& grids, double tol) {
  struct Entry {
    double z;
    int grid, index;
  };
  std::vector<Entry> all;
  for (std::size_t g = 0; g < grids.size(); ++g)
    for (const Level& l : grids[g].at) all.push_back({l.z(), static_cast<int>(g), l.index});
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) {
    return a.z < b.z || (a.z == b.z && a.grid < b.grid);
  });
  std::vector<MergedLevel> out;
  int top = -1; // the last grid among the levels that coincide: its height is kept
  for (const Entry& e : all) {
    if (out.empty() || e.z - out.back().z > tol) {
      out.push_back({e.z, std::vector<int>(grids.size(), -1)});
      top = e.grid;
    } else if (e.grid > top) {
      out.back().z = e.z;
      top = e.grid;
    }
    out.back().index[e.grid] = e.index;
  }
  return out;
}

std::vector<Slab> prism_slabs(const geometry::Prism& body, double spacing, double cell_size,
                              const std::vector<geometry::Refinement>& refinement, double reach) {
  const double tol = 1e-9 * body.size();
  const std::vector<Levels> grids =
      prism_levels(body, cell_size, refinement, cell_size / spacing, reach);
  const std::vector<MergedLevel> levels = merged_levels(grids, tol);
  std::vector<Slab> slabs;
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    const MergedLevel &a = levels[k], &b = levels[k + 1];
    Slab s;
    // A layer of one grid keeps that grid's form (the last box's where several share it), so
    // that a body without 3D boxes gets its points exactly where one loop over its layers did.
    s.lo = Level{a.z, b.z - a.z, 0};
    for (std::size_t g = 0; g < grids.size(); ++g)
      if (a.index[g] >= 0 && b.index[g] == a.index[g] + 1) s.lo = grids[g].at[a.index[g]];
    const double middle = s.z(0.5);
    for (std::size_t i = 0; i < refinement.size(); ++i)
      if (!refinement[i].along_z || grids[i + 1].spans(middle, tol))
        s.boxes.push_back(static_cast<int>(i));
    slabs.push_back(std::move(s));
  }
  return slabs;
}

} // namespace mf::implicit
