#include "meshfree/implicit/solid_points.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/geometry/box_clip.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/solid_sphere_points.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <cmath>
#include <map>

namespace mf::implicit {

namespace {

quadrature::CellSizing sizing_of(const spec::DiscretisationSpec& d) {
  return {d.spacing, d.refinement, d.cell_size / d.spacing, d.dilation.maxCoeff()};
}

/// The cells' sizes in a slab: those of the refinement boxes that refine it.
quadrature::CellSizing sizing_of(const spec::DiscretisationSpec& d, const Slab& slab) {
  quadrature::CellSizing s = sizing_of(d);
  s.refinement = boxes_of(slab.boxes, d.refinement);
  return s;
}

/// The slabs of the body's integration cells along z.
std::vector<Slab> cell_slabs(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  return prism_slabs(body, d.spacing, d.cell_size, d.refinement, d.dilation.maxCoeff());
}

/// The section's Gauss points in each slab, made once for each set of refinement boxes.
class SectionPoints {
public:
  SectionPoints(const geometry::Prism& body, const spec::DiscretisationSpec& d)
      : body_(body), d_(d) {}
  const quadrature::DomainPoints& in(const Slab& slab) {
    auto it = made_.find(slab.boxes);
    if (it == made_.end())
      it = made_
               .emplace(slab.boxes,
                        quadrature::domain_points(body_.section, d_.cell_size, d_.order,
                                                  d_.cut_levels, sizing_of(d_, slab), d_.cut_arcs))
               .first;
    return it->second;
  }

private:
  const geometry::Prism& body_;
  const spec::DiscretisationSpec& d_;
  std::map<std::vector<int>, quadrature::DomainPoints> made_;
};

/// The interval of z from z0 to z1.
struct Span {
  double z0, z1;
  double length() const { return z1 - z0; }
};

/// The parts of the slabs within `span` (a slab cut by its ends as a slab of its own).
std::vector<Slab> slabs_in(const std::vector<Slab>& slabs, const Span& span, double tol) {
  std::vector<Slab> out;
  for (const Slab& s : slabs) {
    const double z0 = std::max(s.z(0.0), span.z0), z1 = std::min(s.z(1.0), span.z1);
    if (z1 - z0 <= tol) continue;
    out.push_back(s);
    if (z0 > s.z(0.0) + tol || z1 < s.z(1.0) - tol) out.back().lo = Level{z0, z1 - z0, 0};
  }
  return out;
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
            s.radius &&
        r.z_lo < s.center.z() + s.radius && r.z_hi > s.center.z() - s.radius)
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

/// The side faces over the plane `sides` through `slabs`: each slab's boundary points of the
/// section (refined as the slab's boxes ask) times its Gauss points along z.
template <class Add>
void side_points(const spec::DiscretisationSpec& d, const std::vector<geometry::Curve>& sides,
                 const std::vector<Slab>& slabs, Add&& add) {
  const GaussRule& g = gauss_legendre(d.boundary_order);
  std::map<std::vector<int>, quadrature::BoundaryPoints> made;
  for (const Slab& slab : slabs) {
    auto it = made.find(slab.boxes);
    if (it == made.end())
      it = made.emplace(slab.boxes, quadrature::boundary_points(
                                        sides, d.cell_size, d.boundary_order, sizing_of(d, slab)))
               .first;
    const quadrature::BoundaryPoints& edge = it->second;
    for (std::size_t q = 0; q < g.points.size(); ++q) {
      const double z = slab.z(0.5 * (g.points[q] + 1.0)), wz = 0.5 * slab.thickness() * g.weights[q];
      for (std::size_t k = 0; k < edge.x.size(); ++k)
        add(Vec3(edge.x[k].x(), edge.x[k].y(), z), edge.weight[k] * wz,
            Vec3(edge.normal[k].x(), edge.normal[k].y(), 0.0));
    }
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
  // A rounded corner stays where the box holds it whole, and is left out where the box misses
  // the region between the corner and its arc.
  for (const geometry::Fillet& f : section.fillets()) {
    const std::vector<Vec2> cap{v[f.vertex], f.from, f.center, f.to};
    if (std::all_of(cap.begin(), cap.end(), [&](const Vec2& x) { return b.contains(x, tol); }))
      in.round_corner(v[f.vertex], f.radius, f.name);
    else
      MF_REQUIRE(std::abs(geometry::signed_area(geometry::clip_polygon(cap, b))) <= tol * tol,
                 "a box cuts the rounded corner ", f.name,
                 " of an end face: a box holds the whole of a fillet or none of it");
  }
  in.add_holes_of(section);
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
                                       const std::vector<Slab>& slabs, SectionPoints& section) {
  const GaussRule& g = gauss_legendre(d.order);
  SolidPoints p;
  int first_cell = 0;
  for (const Slab& slab : slabs) {
    const quadrature::DomainPoints& plane = section.in(slab);
    std::vector<BoundingBox> cells(plane.cell_count, BoundingBox{Vec2::Zero(), Vec2::Zero()});
    for (std::size_t k = 0; k < plane.x.size(); ++k)
      cells[plane.cell[k]] = plane_cell(body.section, d.cell_size, plane.cell[k], plane.x[k]);
    const double z0 = slab.z(0.0), dz = slab.thickness();
    std::vector<char> touched(cells.size(), 0);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const Vec3 lo(cells[c].lo.x(), cells[c].lo.y(), z0),
          hi(cells[c].hi.x(), cells[c].hi.y(), z0 + dz);
      if (cells[c].size().isZero() || !sphere_touches(body, lo, hi)) continue;
      touched[c] = 1;
      sphere_cell_points(body, lo, hi, d.order, d.cut_levels, sizing_of(d, slab), p);
      p.cell.resize(p.x.size(), first_cell + static_cast<int>(c));
    }
    for (std::size_t q = 0; q < g.points.size(); ++q) {
      const double z = z0 + 0.5 * (g.points[q] + 1.0) * dz, wz = 0.5 * dz * g.weights[q];
      for (std::size_t k = 0; k < plane.x.size(); ++k) {
        if (touched[plane.cell[k]]) continue;
        p.x.emplace_back(plane.x[k].x(), plane.x[k].y(), z);
        p.weight.push_back(plane.weight[k] * wz);
        p.cell.push_back(first_cell + plane.piece[k]);
      }
    }
    first_cell += plane.piece_count;
  }
  return p;
}

} // namespace

namespace {

/// The refinement boxes that refine the section's cloud at height z: every box given in the
/// plane; one given in 3D on the levels of its range but at an end of it inside the body, where
/// the coarser cloud stands (its supports reach the base layer beyond).
std::vector<int> boxes_at(const geometry::Prism& body, const spec::DiscretisationSpec& d,
                          const std::vector<Levels>& grids, double z, double tol) {
  std::vector<int> boxes;
  for (std::size_t i = 0; i + 1 < grids.size(); ++i) {
    const Levels& g = grids[i + 1];
    if (!d.refinement[i].along_z) {
      boxes.push_back(static_cast<int>(i));
      continue;
    }
    if (!g.spans(z, tol)) continue;
    const bool inner_end = (z <= g.at.front().z() + tol && z > body.z0 + tol) ||
                           (z >= g.at.back().z() - tol && z < body.z1() - tol);
    if (!inner_end) boxes.push_back(static_cast<int>(i));
  }
  return boxes;
}

/// The grid whose levels a node of `spacing` stands on, among the base's and those of `boxes`:
/// the finest at least as coarse as the node (a box given in the plane has no levels: its nodes
/// stand on the base's).
int own_grid(const std::vector<Levels>& grids, const std::vector<int>& boxes, double spacing) {
  int own = 0;
  for (int b : boxes)
    if (!grids[b + 1].at.empty() && grids[b + 1].spacing >= spacing * (1.0 - 1e-9) &&
        grids[b + 1].spacing < grids[own].spacing)
      own = b + 1;
  return own;
}

} // namespace

std::vector<MergedLevel> node_levels(const geometry::Prism& body,
                                     const spec::DiscretisationSpec& d) {
  return merged_levels(prism_levels(body, d.spacing, d.refinement, 1.0, 0.0), 1e-9 * body.size());
}

SolidNodes prism_nodes(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  const double tol = 1e-9 * body.size();
  const std::vector<Levels> grids = prism_levels(body, d.spacing, d.refinement, 1.0, 0.0);
  std::map<std::vector<int>, geometry::NodeCloud> clouds;
  SolidNodes n;
  // Level-major order: contiguous ranges of nodes are slabs, which keeps the partition over
  // ranks compact.
  for (const MergedLevel& level : merged_levels(grids, tol)) {
    const std::vector<int> boxes = boxes_at(body, d, grids, level.z, tol);
    auto it = clouds.find(boxes);
    if (it == clouds.end())
      it = clouds
               .emplace(boxes, geometry::generate_nodes(body.section, d.spacing,
                                                        boxes_of(boxes, d.refinement)))
               .first;
    const geometry::NodeCloud& plane = it->second;
    for (std::size_t i = 0; i < plane.x.size(); ++i) {
      const int own = own_grid(grids, boxes, plane.spacing[i]);
      const int k = level.index[own];
      if (k < 0) continue; // a level of finer layers than the node's
      const double below = grids[own].below(k), above = grids[own].above(k);
      n.x.emplace_back(plane.x[i].x(), plane.x[i].y(), grids[own].at[k].z());
      n.spacing.push_back(std::max(plane.spacing[i], std::max(below, above)));
      n.volume.push_back(plane.volume[i] * (0.5 * (below + above)));
    }
  }
  if (!body.spheres.empty()) fit_nodes_to_spheres(body, d, n);
  return n;
}

SolidPoints prism_volume_points(const geometry::Prism& body, const spec::DiscretisationSpec& d) {
  const std::vector<Slab> slabs = cell_slabs(body, d);
  SectionPoints section(body, d);
  if (!body.spheres.empty()) return volume_points_with_spheres(body, d, slabs, section);
  const GaussRule& g = gauss_legendre(d.order);
  SolidPoints p;
  int first_cell = 0;
  for (const Slab& slab : slabs) {
    const quadrature::DomainPoints& plane = section.in(slab);
    for (std::size_t q = 0; q < g.points.size(); ++q) {
      const double z = slab.z(0.5 * (g.points[q] + 1.0)), wz = 0.5 * slab.thickness() * g.weights[q];
      for (std::size_t k = 0; k < plane.x.size(); ++k) {
        p.x.emplace_back(plane.x[k].x(), plane.x[k].y(), z);
        p.weight.push_back(plane.weight[k] * wz);
        p.cell.push_back(first_cell + plane.piece[k]);
      }
    }
    first_cell += plane.piece_count;
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
  const std::vector<Slab> slabs = cell_slabs(body, d);
  if (!sides.empty()) side_points(d, sides, slabs_in(slabs, span, tol), add);
  for (const bool back : {true, false}) {
    if (!named(back ? "back" : "front")) continue;
    const double z = back ? body.z0 : body.z1();
    const std::optional<geometry::Domain> section = end_in_box(body, z, box, tol);
    if (!section) continue;
    const Slab& next = back ? slabs.front() : slabs.back();
    const quadrature::DomainPoints end = quadrature::domain_points(
        *section, d.cell_size, d.boundary_order, d.cut_levels, sizing_of(d, next), d.cut_arcs);
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
