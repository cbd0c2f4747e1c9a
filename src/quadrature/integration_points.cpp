#include "meshfree/quadrature/integration_points.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/quadrature/arc_cut_cells.hpp"
#include <cmath>

namespace mf::quadrature {

namespace {

/// Calls f(quarter) for the four quarters of `box`.
template <class F> void for_each_quarter(const BoundingBox& box, F&& f) {
  const Vec2 half = 0.5 * box.size();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const Vec2 lo = box.lo + Vec2(i * half.x(), j * half.y());
      f(BoundingBox{lo, lo + half});
    }
}

/// True where one of the curves may pass through `box`: a segment crosses its interior by more
/// than `tol`, or an arc's circle does. An arc tangent to a cell's side (a fillet or a slot's end
/// drawn on the cells' lines, or a curve read from a file, whose rounding may cross the side by
/// 1e-14) does not cut the cell.
bool curves_meet(const std::vector<geometry::Curve>& curves, const BoundingBox& box, double tol) {
  const Vec2 mid = 0.5 * (box.lo + box.hi), half = 0.5 * box.size();
  for (const geometry::Curve& c : curves) {
    if (c.kind == geometry::Curve::Kind::Segment) {
      if (segment_crosses_interior(box, c.a, c.b, tol)) return true;
      continue;
    }
    const Vec2 nearest = c.center.cwiseMax(box.lo).cwiseMin(box.hi);
    const double far = ((c.center - mid).cwiseAbs() + half).norm();
    if ((nearest - c.center).norm() < c.radius - tol && far > c.radius + tol) return true;
  }
  return false;
}

/// True where an arc of the outline (a rounded corner's, or one drawn so) may pass through `box`.
bool outline_arc_meets(const geometry::Domain& domain, const BoundingBox& box, double tol) {
  for (const geometry::Curve& c : domain.outline())
    if (c.kind == geometry::Curve::Kind::Arc && curves_meet({c}, box, tol)) return true;
  return false;
}

/// The one hole that cuts `box` when nothing else of the boundary does (the box lies in the
/// polygon and meets no other hole), or null.
const geometry::Circle* only_cutting_hole(const geometry::Domain& domain, const BoundingBox& box) {
  const double tol = 1e-9 * box.size().maxCoeff();
  for (const auto& h : domain.outline_holes())
    if (curves_meet(h.loop(), box, tol)) return nullptr;
  const geometry::Circle* found = nullptr;
  for (const auto& h : domain.holes()) {
    const Vec2 nearest = h.center.cwiseMax(box.lo).cwiseMin(box.hi);
    if ((nearest - h.center).norm() >= h.radius - tol) continue;
    if (found) return nullptr;
    found = &h;
  }
  if (!found) return nullptr;
  for (const Vec2& p : {box.lo, Vec2(box.hi.x(), box.lo.y()), box.hi, Vec2(box.lo.x(), box.hi.y())})
    if (!domain.within_outline(p, 1e-9)) return nullptr;
  return curves_meet(domain.outline(), box, tol) ? nullptr : found;
}

/// Adds the Gauss points of `box` that lie in the body; splits cells the boundary cuts, or
/// with `arcs` integrates a cell cut by one hole on its exact region. The points belong to
/// background cell `cell_id` and to piece `piece`; quarters that refinement asks for become
/// pieces of their own (numbered on from out.piece_count).
void integrate_cell(const geometry::Domain& domain, const BoundingBox& box, const GaussRule& g,
                    int levels_left, int cell_id, int piece, const CellSizing& sizing, bool arcs,
                    DomainPoints& out) {
  const Vec2 half = 0.5 * box.size();
  const Vec2 mid = box.lo + half;
  if (sizing.spacing > 0.0 && box.size().maxCoeff() > sizing.size_at(box) * (1.0 + 1e-9)) {
    // refined nodes need refined integration
    for_each_quarter(box, [&](const BoundingBox& q) {
      integrate_cell(domain, q, g, levels_left, cell_id, out.piece_count++, sizing, arcs, out);
    });
    return;
  }
  const int n = static_cast<int>(g.points.size());
  // Sample corners and Gauss points: a mixed verdict means the boundary crosses the cell.
  int inside = 0, total = 0;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i, ++total)
      inside += domain.contains(box.lo + Vec2(i * box.size().x(), j * box.size().y())) ? 1 : 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i, ++total)
      inside += domain.contains(mid + Vec2(g.points[i] * half.x(), g.points[j] * half.y())) ? 1 : 0;
  bool cut = inside > 0 && inside < total;
  for (const auto& h : domain.holes()) { // a hole may touch the cell between the samples
    const Vec2 nearest = h.center.cwiseMax(box.lo).cwiseMin(box.hi);
    const double far = ((h.center - mid).cwiseAbs() + half).norm(); // farthest corner
    if ((nearest - h.center).norm() < h.radius && far > h.radius) cut = true;
  }
  for (const auto& h : domain.outline_holes())
    cut = cut || curves_meet(h.loop(), box, 1e-9 * box.size().maxCoeff());
  cut = cut || outline_arc_meets(domain, box, 1e-9 * box.size().maxCoeff());
  if (cut && arcs) {
    if (const geometry::Circle* hole = only_cutting_hole(domain, box)) {
      cell_minus_disc(box, hole->center, hole->radius, g, out.x, out.weight);
      out.cell.resize(out.x.size(), cell_id);
      out.piece.resize(out.x.size(), piece);
      return;
    }
  }
  if (cut && levels_left > 0) {
    for_each_quarter(box, [&](const BoundingBox& q) {
      integrate_cell(domain, q, g, levels_left - 1, cell_id, piece, sizing, arcs, out);
    });
    return;
  }
  if (inside == 0 && !cut) return;
  const double jac = half.x() * half.y();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 p = mid + Vec2(g.points[i] * half.x(), g.points[j] * half.y());
      if (!domain.contains(p)) continue;
      out.x.push_back(p);
      out.weight.push_back(g.weights[i] * g.weights[j] * jac);
      out.cell.push_back(cell_id);
      out.piece.push_back(piece);
    }
}

} // namespace

double CellSizing::size_at(const BoundingBox& box) const {
  double h = spacing;
  for (const auto& r : refinement) {
    const double m = reach * r.spacing;
    if (box.lo.x() < r.box.hi.x() + m && box.hi.x() > r.box.lo.x() - m &&
        box.lo.y() < r.box.hi.y() + m && box.hi.y() > r.box.lo.y() - m)
      h = std::min(h, r.spacing);
  }
  return ratio * h;
}

DomainPoints domain_points(const geometry::Domain& domain, double cell_size, int order,
                           int cut_levels, const CellSizing& sizing, bool arcs) {
  MF_REQUIRE(cell_size > 0.0, "integration cell size must be positive, got ", cell_size);
  MF_REQUIRE(cut_levels >= 0 && cut_levels <= 6, "cut-cell levels must be in [0, 6], got ",
             cut_levels);
  const GaussRule& g = gauss_legendre(order);
  const BoundingBox bb = domain.bounds();
  const int nx = std::max(1, static_cast<int>(std::ceil(bb.size().x() / cell_size - 1e-9)));
  const int ny = std::max(1, static_cast<int>(std::ceil(bb.size().y() / cell_size - 1e-9)));
  const Vec2 h(bb.size().x() / nx, bb.size().y() / ny); // cells fit the box exactly
  DomainPoints out;
  out.cell_count = out.piece_count = nx * ny;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      BoundingBox box{bb.lo + Vec2(i * h.x(), j * h.y()), Vec2::Zero()};
      box.hi = box.lo + h;
      integrate_cell(domain, box, g, cut_levels, j * nx + i, j * nx + i, sizing, arcs, out);
    }
  return out;
}

BoundaryPoints boundary_points(const std::vector<geometry::Curve>& pieces, double part_length,
                               int order, const CellSizing& sizing) {
  MF_REQUIRE(part_length > 0.0, "boundary part length must be positive, got ", part_length);
  const GaussRule& g = gauss_legendre(order);
  BoundaryPoints out;
  for (const auto& whole : pieces)
    for (const auto& c : geometry::split_at_refinements(whole, sizing.refinement)) {
      double length = part_length;
      if (sizing.spacing > 0.0) {
        const Vec2 m = c.point(0.5);
        length = std::min(length, sizing.size_at({m, m}));
      }
      const int parts = std::max(1, static_cast<int>(std::ceil(c.length() / length - 1e-9)));
      const double dt = 1.0 / parts;
      for (int p = 0; p < parts; ++p)
        for (std::size_t q = 0; q < g.points.size(); ++q) {
          const double t = (p + 0.5 * (g.points[q] + 1.0)) * dt;
          out.x.push_back(c.point(t));
          out.weight.push_back(g.weights[q] * 0.5 * dt * c.speed());
          out.normal.push_back(c.outward_normal(t));
        }
    }
  return out;
}

} // namespace mf::quadrature
