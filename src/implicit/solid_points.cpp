#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/geometry/box_clip.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/solid_sphere_points.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <cmath>

namespace mf::implicit {

namespace {

quadrature::CellSizing sizing_of(const spec::DiscretisationSpec& d) {
  return {d.spacing, d.refinement, d.cell_size / d.spacing, d.dilation.maxCoeff()};
}

/// The interval of z from z0 to z1.
struct Span {
  double z0, z1;
  double length() const { return z1 - z0; }
};

/// Points (z, weight) of `order` Gauss points in each of round(length / spacing) layers (at least
/// one) of `span`.
std::vector<std::pair<double, double>> through(const Span& span, double spacing, int order) {
  const int layers = std::max(1, static_cast<int>(std::lround(span.length() / spacing)));
  const double dz = span.length() / layers;
  const GaussRule& g = gauss_legendre(order);
  std::vector<std::pair<double, double>> out;
  for (int l = 0; l < layers; ++l)
    for (std::size_t q = 0; q < g.points.size(); ++q)
      out.emplace_back(span.z0 + (l + 0.5 * (g.points[q] + 1.0)) * dz, 0.5 * dz * g.weights[q]);
  return out;
}

/// Points (z, weight) of `order` Gauss points in each of the body's layers.
std::vector<std::pair<double, double>> through_depth(const geometry::Prism& body, double spacing,
                                                     int order) {
  return through({body.z0, body.z1()}, spacing, order);
}

bool kept(const std::optional<spec::Box>& box, const Vec3& x, double tol) {
  return !box || box->contains(x, tol);
}

BoundingBox plane_box(const spec::Box& box) {
  return {box.lo.head<2>(), box.hi.head<2>()};
}

/// The depth of the body inside the box (all of it without one).
Span depth_in(const geometry::Prism& body, const std::optional<spec::Box>& box) {
  if (!box) return {body.z0, body.z1()};
  return {std::max(body.z0, box->lo.z()), std::min(body.z1(), box->hi.z())};
}

/// The parts of boundary piece `c` inside the box's plane footprint (all of c without a box).
std::vector<geometry::Curve> parts_in_box(const geometry::Curve& c,
                                          const std::optional<spec::Box>& box, double tol) {
  if (!box) return {c};
  const BoundingBox b = plane_box(*box);
  std::vector<geometry::Curve> parts;
  if (c.kind == geometry::Curve::Kind::Segment) {
    if (const auto t = geometry::clip_segment(c.a, c.b, b, tol))
      parts.push_back(t->first == 0.0 && t->second == 1.0 ? c : c.piece(t->first, t->second));
    return parts;
  }
  // An arc meets a side of the box at most tangentially: the box itself bounds it.
  for (const auto& [t0, t1] :
       geometry::kept_intervals(c, [&](const Vec2& x) { return b.contains(x); }))
    parts.push_back(c.piece(t0, t1));
  return parts;
}

// Lattice nodes nearer a sphere's surface than this many local spacings are left out (the plane
// node cloud's gap at its boundary, geometry/node_generation).
constexpr double kSphereGap = 0.3;

/// The finest node spacing wanted near the sphere: the base spacing, or that of a refinement
/// box its footprint meets.
double spacing_near(const geometry::Sphere& s, const spec::DiscretisationSpec& d) {
  double h = d.spacing;
  for (const geometry::Refinement& r : d.refinement)
    if ((s.center.head<2>().cwiseMax(r.box.lo).cwiseMin(r.box.hi) - s.center.head<2>()).norm() <
        s.radius)
      h = std::min(h, r.spacing);
  return h;
}

/// Lattice nodes of the spheres' balls and of their gaps replaced by nodes on their surfaces.
void fit_nodes_to_spheres(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                          SolidNodes& n) {
  SolidNodes kept;
  for (std::size_t i = 0; i < n.x.size(); ++i) {
    const bool clear =
        std::all_of(body.spheres.begin(), body.spheres.end(), [&](const geometry::Sphere& s) {
          return s.distance(n.x[i]) >= kSphereGap * n.spacing[i];
        });
    if (!clear) continue;
    kept.x.push_back(n.x[i]);
    kept.spacing.push_back(n.spacing[i]);
    kept.volume.push_back(n.volume[i]);
  }
  for (const geometry::Sphere& s : body.spheres) {
    const double h = spacing_near(s, d);
    for (const Vec3& x : geometry::sphere_surface_points(body, s, h)) {
      kept.x.push_back(x);
      kept.spacing.push_back(h);
      kept.volume.push_back(0.5 * h * h * h); // half a lattice cell: the body is on one side
    }
  }
  n = std::move(kept);
}

/// The body's section at height z: the plane section minus each sphere's disc there, so that an
/// end face cut by a sphere is integrated as a plane body with a hole.
geometry::Domain end_section(const geometry::Prism& body, double z) {
  geometry::Domain section = body.section;
  for (const geometry::Sphere& s : body.spheres) {
    const double h = z - s.center.z();
    const double rho2 = s.radius * s.radius - h * h;
    if (rho2 > 1e-18 * body.size() * body.size())
      section.add_hole({s.center.head<2>(), std::sqrt(rho2), s.name});
  }
  return section;
}

/// True when a sphere's ball meets the side face over the straight piece `c`.
bool sphere_cuts_side(const geometry::Prism& body, const geometry::Curve& c) {
  if (c.kind != geometry::Curve::Kind::Segment) return false;
  return std::any_of(body.spheres.begin(), body.spheres.end(), [&](const geometry::Sphere& s) {
    const double dz = std::max({body.z0 - s.center.z(), s.center.z() - body.z1(), 0.0});
    const double d = c.distance_to(s.center.head<2>());
    return d * d + dz * dz < s.radius * s.radius;
  });
}

/// The side face over the straight piece `c` through `span`, which spheres cut: the rectangle
/// (arc length along c) x (span) minus each sphere's disc in its plane, integrated as a plane body
/// with holes (exact arcs where the discretisation asks for them); `add(x, weight, normal)` takes
/// each point.
template <class Add>
void side_cut_by_spheres(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                         const geometry::Curve& c, const Span& span, Add&& add) {
  const double length = c.length();
  geometry::Domain face = geometry::Domain::rectangle({0.0, 0.0}, {length, span.length()});
  const Vec2 along = (c.b - c.a) / length;
  for (const geometry::Sphere& s : body.spheres) {
    const Vec2 rel = s.center.head<2>() - c.a;
    const double t = rel.dot(along), off = rel.x() * along.y() - rel.y() * along.x();
    const double rho2 = s.radius * s.radius - off * off;
    if (rho2 > 1e-18 * body.size() * body.size())
      face.add_hole({Vec2(t, s.center.z() - span.z0), std::sqrt(rho2), s.name});
  }
  const Vec2 m = c.point(0.5);
  const double cell = std::min(d.cell_size, sizing_of(d).size_at({m, m}));
  const quadrature::DomainPoints on =
      quadrature::domain_points(face, cell, d.boundary_order, d.cut_levels, {}, d.cut_arcs);
  const Vec2 n = c.outward_normal(0.5);
  for (std::size_t k = 0; k < on.x.size(); ++k) {
    const Vec2 xy = c.a + on.x[k].x() * along;
    add(Vec3(xy.x(), xy.y(), span.z0 + on.x[k].y()), on.weight[k], Vec3(n.x(), n.y(), 0.0));
  }
}

/// The end section at height z cut to the box's footprint; none when the box leaves nothing of
/// positive area of it (or misses the plane z).
std::optional<geometry::Domain> end_in_box(const geometry::Prism& body, double z,
                                           const std::optional<spec::Box>& box, double tol) {
  geometry::Domain section = end_section(body, z);
  if (!box) return section;
  if (z < box->lo.z() - tol || z > box->hi.z() + tol) return std::nullopt;
  const BoundingBox b = plane_box(*box);
  const std::vector<Vec2>& v = section.vertices();
  if (std::all_of(v.begin(), v.end(), [&](const Vec2& x) { return b.contains(x, tol); }))
    return section;
  const std::vector<Vec2> cut = geometry::clip_polygon(v, b);
  if (cut.size() < 3 || std::abs(geometry::signed_area(cut)) <= tol * tol) return std::nullopt;
  geometry::Domain in = geometry::Domain::polygon(cut);
  for (const geometry::Circle& h : section.holes()) in.add_hole(h);
  return in;
}

/// The plane cell of the quadrature's grid (quadrature::domain_points: cells of about
/// `cell_size` fitted to the section's bounding box) that holds plane point `x`, numbered `cell`.
BoundingBox plane_cell(const geometry::Domain& section, double cell_size, int cell, const Vec2& x) {
  const BoundingBox bb = section.bounds();
  const int nx = std::max(1, static_cast<int>(std::ceil(bb.size().x() / cell_size - 1e-9)));
  const int ny = std::max(1, static_cast<int>(std::ceil(bb.size().y() / cell_size - 1e-9)));
  const Vec2 h(bb.size().x() / nx, bb.size().y() / ny);
  const Vec2 lo = bb.lo + Vec2((cell % nx) * h.x(), (cell / nx) * h.y());
  const BoundingBox box{lo, lo + h};
  const double tol = 1e-9 * h.maxCoeff();
  MF_REQUIRE(x.x() >= box.lo.x() - tol && x.x() <= box.hi.x() + tol && x.y() >= box.lo.y() - tol &&
                 x.y() <= box.hi.y() + tol,
             "the plane quadrature's cell ", cell, " does not hold its point");
  return box;
}

/// The volume points of a body with spheres: the plane points times the rule along z where no
/// sphere touches the cell they came from, and the touched cells integrated anew.
SolidPoints volume_points_with_spheres(const geometry::Prism& body,
                                       const spec::DiscretisationSpec& d,
                                       const quadrature::DomainPoints& plane) {
  const int layers = layer_count(body, d.cell_size);
  const double dz = body.depth / layers;
  const GaussRule& g = gauss_legendre(d.order);
  std::vector<BoundingBox> cells(plane.cell_count, BoundingBox{Vec2::Zero(), Vec2::Zero()});
  for (std::size_t k = 0; k < plane.x.size(); ++k)
    cells[plane.cell[k]] = plane_cell(body.section, d.cell_size, plane.cell[k], plane.x[k]);
  SolidPoints p;
  for (int l = 0; l < layers; ++l) {
    const double z0 = body.z0 + l * dz;
    std::vector<char> touched(cells.size(), 0);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const Vec3 lo(cells[c].lo.x(), cells[c].lo.y(), z0),
          hi(cells[c].hi.x(), cells[c].hi.y(), z0 + dz);
      if (cells[c].size().isZero() || !sphere_touches(body, lo, hi)) continue;
      touched[c] = 1;
      sphere_cell_points(body, lo, hi, d.order, d.cut_levels, sizing_of(d), p);
      p.cell.resize(p.x.size(), l * plane.piece_count + static_cast<int>(c));
    }
    for (std::size_t q = 0; q < g.points.size(); ++q) {
      const double z = z0 + 0.5 * (g.points[q] + 1.0) * dz, wz = 0.5 * dz * g.weights[q];
      for (std::size_t k = 0; k < plane.x.size(); ++k) {
        if (touched[plane.cell[k]]) continue;
        p.x.emplace_back(plane.x[k].x(), plane.x[k].y(), z);
        p.weight.push_back(plane.weight[k] * wz);
        p.cell.push_back(l * plane.piece_count + plane.piece[k]);
      }
    }
  }
  return p;
}

} // namespace

int layer_count(const geometry::Prism& body, double spacing) {
  return std::max(1, static_cast<int>(std::lround(body.depth / spacing)));
}

SolidNodes prism_nodes(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  const geometry::NodeCloud plane = geometry::generate_nodes(body.section, d.spacing, d.refinement);
  const int layers = layer_count(body, d.spacing);
  const double dz = body.depth / layers;
  SolidNodes n;
  // Layer-major order: contiguous ranges of nodes are slabs, which keeps the partition over
  // ranks compact.
  for (int l = 0; l <= layers; ++l) {
    const double end = (l == 0 || l == layers) ? 0.5 : 1.0;
    for (std::size_t i = 0; i < plane.x.size(); ++i) {
      n.x.emplace_back(plane.x[i].x(), plane.x[i].y(), body.z0 + l * dz);
      n.spacing.push_back(std::max(plane.spacing[i], dz));
      n.volume.push_back(plane.volume[i] * dz * end);
    }
  }
  if (!body.spheres.empty()) fit_nodes_to_spheres(body, d, n);
  return n;
}

SolidPoints prism_volume_points(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  const quadrature::DomainPoints plane = quadrature::domain_points(
      body.section, d.cell_size, d.order, d.cut_levels, sizing_of(d), d.cut_arcs);
  if (!body.spheres.empty()) return volume_points_with_spheres(body, d, plane);
  SolidPoints p;
  const std::vector<std::pair<double, double>> along_z = through_depth(body, d.cell_size, d.order);
  for (std::size_t q = 0; q < along_z.size(); ++q) {
    const int layer = static_cast<int>(q) / d.order;
    for (std::size_t k = 0; k < plane.x.size(); ++k) {
      p.x.emplace_back(plane.x[k].x(), plane.x[k].y(), along_z[q].first);
      p.weight.push_back(plane.weight[k] * along_z[q].second);
      p.cell.push_back(layer * plane.piece_count + plane.piece[k]);
    }
  }
  return p;
}

SolidPoints prism_face_points(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                              const std::vector<std::string>& faces,
                              const std::optional<spec::Box>& box) {
  const double tol = 1e-9 * std::max(body.depth, body.section.bounds().size().maxCoeff());
  const auto named = [&faces](const std::string& n) {
    return std::find(faces.begin(), faces.end(), n) != faces.end();
  };
  SolidPoints p;
  const auto add = [&](const Vec3& x, double w, const Vec3& n) {
    if (!body.outside_spheres(x, 1e-9)) return;
    p.x.push_back(x);
    p.weight.push_back(w);
    p.normal.push_back(n);
  };
  // The sides and ends are integrated over their parts inside the box, so that the box's edges
  // bound the loaded area wherever they fall among the background cells.
  const Span span = depth_in(body, box);
  std::vector<geometry::Curve> sides;
  for (const geometry::Curve& c : body.section.boundary()) {
    if (!named(c.name) || span.length() <= tol) continue;
    for (const geometry::Curve& part : parts_in_box(c, box, tol)) {
      if (sphere_cuts_side(body, part))
        side_cut_by_spheres(body, d, part, span, add);
      else
        sides.push_back(part);
    }
  }
  if (!sides.empty()) {
    const quadrature::BoundaryPoints edge =
        quadrature::boundary_points(sides, d.cell_size, d.boundary_order, sizing_of(d));
    for (const auto& [z, wz] : through(span, d.cell_size, d.boundary_order))
      for (std::size_t k = 0; k < edge.x.size(); ++k)
        add(Vec3(edge.x[k].x(), edge.x[k].y(), z), edge.weight[k] * wz,
            Vec3(edge.normal[k].x(), edge.normal[k].y(), 0.0));
  }
  for (const bool back : {true, false}) {
    if (!named(back ? "back" : "front")) continue;
    const double z = back ? body.z0 : body.z1();
    const std::optional<geometry::Domain> section = end_in_box(body, z, box, tol);
    if (!section) continue;
    const quadrature::DomainPoints end = quadrature::domain_points(
        *section, d.cell_size, d.boundary_order, d.cut_levels, sizing_of(d), d.cut_arcs);
    for (std::size_t k = 0; k < end.x.size(); ++k)
      add(Vec3(end.x[k].x(), end.x[k].y(), z), end.weight[k], Vec3(0.0, 0.0, back ? -1.0 : 1.0));
  }
  for (const geometry::Sphere& s : body.spheres) {
    if (!named(s.name)) continue;
    const SolidPoints on = sphere_face_points(body, s, d.cell_size, d.boundary_order, d.cut_levels);
    const auto in = [&](const Vec3& x) { return kept(box, x, tol); };
    const std::size_t count = std::count_if(on.x.begin(), on.x.end(), in);
    MF_REQUIRE(count == 0 || count == on.x.size(), "a box cuts the surface of sphere ", s.name,
               ": a box holds the whole of a sphere's face or none of it");
    for (std::size_t k = 0; k < on.x.size(); ++k)
      if (in(on.x[k])) add(on.x[k], on.weight[k], on.normal[k]);
  }
  return p;
}

} // namespace mf::implicit
