// A 3D preload as the explicit stage sees it (stages/preload.hpp): the particles carried through
// its increments as passive material points (the material update from their own history, as its
// Gauss points are), and its face conditions on particle layers chosen by their distance to the
// faces.
#include "meshfree/core/error.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/stages/preload.hpp"
#include <algorithm>
#include <cmath>

namespace mf::stages {

PreloadAtParticles SolidPreload::sample(const std::vector<Vec3>& x,
                                        const spec::StageLink& link) const {
  const implicit::SolidModel& model = *r_.model;
  const int np = static_cast<int>(x.size());
  const int N = static_cast<int>(r_.increments.size()) - 1;
  MF_REQUIRE(N >= 1, link.key_path, ": the preload has no converged increment to start from");
  for (int n = 1; n <= N; ++n)
    MF_REQUIRE(r_.increments[n].record.parameters.size() == r_.parameters.size(), link.key_path,
               ": the preload did not record its increments");
  Vec3 inside = Vec3::Zero();
  for (const Vec3& p : model.node_positions()) inside += p;
  inside /= static_cast<double>(model.node_count());
  PreloadAtParticles out = unloaded_preload(N, mirror_into(x, link.mirror, inside));
  std::vector<Vec3> points(np);
  for (int p = 0; p < np; ++p) points[p] = out.image[p].x;
  implicit::SolidShapeTable table;
  try {
    table = implicit::solid_shapes_at(model, points, true);
  } catch (const Error& e) {
    fail(link.key_path, ": a particle lies outside the preload's body (", e.what(), ")");
  }
  const std::vector<double> zero(r_.parameters.size(), 0.0);
#pragma omp parallel for schedule(dynamic, 64)
  for (int p = 0; p < np; ++p) {
    materials::MaterialState committed;
    for (int n = 0; n <= N; ++n) {
      const std::vector<double>& d = n == 0 ? zero : r_.increments[n].record.parameters;
      const materials::StressUpdate3D res =
          implicit::carry_point(table, p, d, r_.material, committed);
      out.u[n][p] = mirrored(implicit::solid_displacement_at(table, p, d), out.image[p]);
      out.stress[n][p] = mirrored(res.stress, out.image[p]);
      out.alpha[n][p] = res.state.alpha;
      if (n == N) out.plastic[p] = res.plastic;
    }
    out.history[p] = mirrored(committed, out.image[p]);
  }
  return out;
}

namespace {

/// Where a face condition lies: its side faces' boundary pieces, whether it covers either end,
/// and the box it is clipped to.
struct FacesOf {
  const geometry::Prism* body = nullptr;
  std::vector<geometry::Curve> sides;
  bool back = false, front = false;
  const std::optional<spec::Box>* box = nullptr;
  double tol = 0.0;
};

FacesOf faces_of(const geometry::Prism& body, const spec::FaceCondition& bc) {
  FacesOf f;
  f.body = &body;
  f.box = &bc.box;
  const auto named = [&](const std::string& n) {
    return std::find(bc.faces.begin(), bc.faces.end(), n) != bc.faces.end();
  };
  for (const geometry::Curve& c : body.section.boundary())
    if (named(c.name)) f.sides.push_back(c);
  f.back = named("back");
  f.front = named("front");
  f.tol = 1e-9 * std::max({1.0, body.depth, body.section.bounds().size().maxCoeff()});
  return f;
}

/// The point of the faces nearest to p among those whose foot lies in the box (a side face's
/// foot: its nearest point at p's height; an end's: p's projection onto it); false if none.
bool nearest_on_faces(const FacesOf& f, const Vec3& p, Vec3& q) {
  double best = -1.0;
  const auto consider = [&](const Vec3& c) {
    if (*f.box && !(*f.box)->contains(c, f.tol)) return;
    const double d = (c - p).norm();
    if (best < 0.0 || d < best) best = d, q = c;
  };
  const double z = std::clamp(p.z(), f.body->z0, f.body->z1());
  for (const geometry::Curve& c : f.sides) {
    const Vec2 s = c.closest_point(p.head<2>());
    consider(Vec3(s.x(), s.y(), z));
  }
  if (f.back) consider(Vec3(p.x(), p.y(), f.body->z0));
  if (f.front) consider(Vec3(p.x(), p.y(), f.body->z1()));
  return best >= 0.0;
}

/// The particles within `depth` of the faces (of any of their images): the image nearest, its
/// distance and the nearest face point.
struct FaceLayer {
  std::vector<int> particles;
  std::vector<double> distance;
  std::vector<Mirrored> how;
  std::vector<Vec3> foot;
};

FaceLayer face_layer(const std::vector<Vec3>& x, const FacesOf& faces,
                     const std::vector<spec::MirrorPlane>& mirror, double depth) {
  FaceLayer l;
  for (std::size_t i = 0; i < x.size(); ++i) {
    double best = depth;
    Mirrored how;
    Vec3 foot;
    bool found = false;
    for (const Mirrored& m : mirror_images(x[i], mirror, 3)) {
      Vec3 q;
      if (!nearest_on_faces(faces, m.x, q)) continue;
      const double d = (q - m.x).norm();
      if (d < best) best = d, how = m, foot = q, found = true;
    }
    if (!found) continue;
    l.particles.push_back(static_cast<int>(i));
    l.distance.push_back(best);
    l.how.push_back(how);
    l.foot.push_back(foot);
  }
  return l;
}

/// Whether every face of the condition lies in the plane x_axis = at (set from the first).
bool on_axis_plane(const FacesOf& f, int axis, double& at) {
  std::vector<double> coordinate;
  for (const geometry::Curve& c : f.sides) {
    if (c.kind != geometry::Curve::Kind::Segment || axis > 1) return false;
    coordinate.push_back(c.a[axis]), coordinate.push_back(c.b[axis]);
  }
  if ((f.back || f.front) && axis != 2) return false;
  if (f.back) coordinate.push_back(f.body->z0);
  if (f.front) coordinate.push_back(f.body->z1());
  if (coordinate.empty()) return false;
  at = coordinate.front();
  for (double c : coordinate)
    if (std::abs(c - at) > f.tol) return false;
  return true;
}

/// A traction or pressure as constant forces on the surface layer: the condition's area shared
/// equally by the layer's particles, each with the preload's final traction at the condition's
/// point nearest to its foot on the faces.
void hold_face_force(HeldCondition& h, const spec::ProblemSpec& preload,
                     const implicit::SolidConditionPoints& c, const FaceLayer& l, double f,
                     std::size_t mirrors) {
  h.kind = HeldCondition::Kind::Force;
  h.particles = l.particles;
  std::vector<int> every(c.points.x.size());
  double area = 0.0;
  for (std::size_t k = 0; k < every.size(); ++k) {
    every[k] = static_cast<int>(k);
    area += c.points.weight[k];
  }
  const std::vector<Vec3> traction = implicit::face_values(preload, *c.bc, c.points, every);
  const double share =
      static_cast<double>(1u << mirrors) * area / static_cast<double>(l.particles.size());
  for (std::size_t j = 0; j < l.particles.size(); ++j) {
    int nearest = 0;
    for (std::size_t k = 1; k < every.size(); ++k)
      if ((c.points.x[k] - l.foot[j]).squaredNorm() <
          (c.points.x[nearest] - l.foot[j]).squaredNorm())
        nearest = static_cast<int>(k);
    const Vec3 t = every.empty() ? Vec3::Zero() : Vec3(f * traction[nearest]);
    h.force.push_back(mirrored(Vec3(share * t), l.how[j]));
  }
}

/// A held displacement: every particle of the layer, those within the surface layer apart; all
/// three components (a clamp) or one (a roller, on an axis plane when its faces are).
void hold_face_displacement(HeldCondition& h, const spec::FaceCondition& bc, const FacesOf& faces,
                            const FaceLayer& l, double f, double surface) {
  h.particles = l.particles;
  for (std::size_t j = 0; j < l.particles.size(); ++j)
    if (l.distance[j] < surface) h.surface.push_back(l.particles[j]);
  const int held = static_cast<int>(bc.mask.sum());
  if (held == 3) {
    h.kind = HeldCondition::Kind::Clamp;
    return;
  }
  h.kind = HeldCondition::Kind::Roller;
  h.component = bc.mask.x() > 0.0 ? 0 : bc.mask.y() > 0.0 ? 1 : 2;
  h.value = f * bc.value[h.component];
  h.on_axis_line = on_axis_plane(faces, h.component, h.line);
}

} // namespace

std::vector<HeldCondition> SolidPreload::held(const spec::StageLink& link,
                                              const std::vector<Vec3>& x,
                                              const HoldLayers& layers) const {
  const implicit::SolidModel& model = *r_.model;
  const std::vector<double>& factor = r_.increments.back().record.factors;
  std::vector<HeldCondition> out;
  for (const std::string& name : link.hold) {
    HeldCondition h;
    h.name = name;
    if (name == "body_force") {
      h.kind = HeldCondition::Kind::Body;
      h.body_factor = factor.back();
      out.push_back(h);
      continue;
    }
    const auto c =
        std::find_if(model.conditions.begin(), model.conditions.end(),
                     [&](const implicit::SolidConditionPoints& p) { return p.bc->name == name; });
    MF_REQUIRE(c != model.conditions.end(), link.key_path, ".hold: no condition '", name, "'");
    const spec::FaceCondition& bc = *c->bc;
    const double f = factor[static_cast<std::size_t>(c - model.conditions.begin())];
    const FacesOf faces = faces_of(model.body, bc);
    const FaceLayer l = face_layer(x, faces, link.mirror, bc.loads ? layers.surface : layers.held);
    if (bc.loads) {
      MF_REQUIRE(!l.particles.empty(), link.key_path, ".hold: no particle lies within ",
                 layers.surface, " of the faces of condition '", name, "'");
      hold_face_force(h, spec(), *c, l, f, link.mirror.size());
      out.push_back(h);
      continue;
    }
    hold_face_displacement(h, bc, faces, l, f, layers.surface);
    // A roller on a mirror plane is the mirror's own symmetry.
    const bool mirror_plane =
        h.kind == HeldCondition::Kind::Roller && h.on_axis_line &&
        std::any_of(link.mirror.begin(), link.mirror.end(), [&](const spec::MirrorPlane& m) {
          return m.axis == h.component && std::abs(m.at - h.line) <= faces.tol;
        });
    if (mirror_plane) continue;
    MF_REQUIRE(!l.particles.empty(), link.key_path, ".hold: no particle lies within ", layers.held,
               " of the faces of condition '", name, "'");
    out.push_back(h);
  }
  return out;
}

materials::IsotropicElastic SolidPreload::elasticity_at(const Vec3&) const {
  return materials::elasticity(r_.material);
}

Vec3 SolidPreload::body_force_at(bool, const Vec3&) const {
  return spec().solid().body_force;
}

} // namespace mf::stages
