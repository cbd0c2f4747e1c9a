#include "meshfree/stages/held_conditions.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/geometry/domain.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include <algorithm>
#include <cmath>

namespace mf::stages {

namespace {

/// The ends of the straight pieces (an arc gives none: it lies on no plane or axis line).
std::vector<Vec2> segment_ends(const std::vector<geometry::Curve>& pieces, bool& all_straight) {
  std::vector<Vec2> ends;
  all_straight = true;
  for (const geometry::Curve& c : pieces) {
    if (c.kind != geometry::Curve::Kind::Segment) all_straight = false;
    ends.push_back(c.a), ends.push_back(c.b);
  }
  return ends;
}

/// Whether every point lies on the line x_axis = at.
bool on_line(const std::vector<Vec2>& pts, int axis, double at, double tol) {
  bool all = !pts.empty();
  for (const Vec2& p : pts) all = all && std::abs(p[axis] - at) <= tol;
  return all;
}

bool on_mirror_plane(const std::vector<Vec2>& ends, bool straight,
                     const std::vector<spec::MirrorPlane>& mirror, double tol) {
  for (const spec::MirrorPlane& m : mirror)
    if (straight && m.axis < 2 && on_line(ends, m.axis, m.at, tol)) return true;
  return false;
}

/// The particles within `depth` of the condition's pieces (of any of their images), with the
/// image that is nearest and its distance.
struct Layer {
  std::vector<int> particles;
  std::vector<double> distance;
  std::vector<Mirrored> how;
};

Layer layer_of(const std::vector<Vec3>& x, const std::vector<geometry::Curve>& pieces,
               const std::vector<spec::MirrorPlane>& mirror, double depth) {
  Layer l;
  for (std::size_t i = 0; i < x.size(); ++i) {
    double best = depth;
    Mirrored how;
    bool found = false;
    for (const Mirrored& m : mirror_images(x[i], mirror, 2))
      for (const geometry::Curve& c : pieces) {
        const double d = c.distance_to(m.x.head<2>());
        if (d < best) best = d, how = m, found = true;
      }
    if (!found) continue;
    l.particles.push_back(static_cast<int>(i));
    l.distance.push_back(best);
    l.how.push_back(how);
  }
  return l;
}

/// The boundary point of the condition nearest to p: where a particle takes its traction. All
/// of the condition's points, not only this rank's: every rank holds the whole body's layer.
int nearest_point(const quadrature::BoundaryPoints& pts, const Vec2& p) {
  int best = -1;
  double d2 = 0.0;
  for (std::size_t k = 0; k < pts.x.size(); ++k) {
    const double e = (pts.x[k] - p).squaredNorm();
    if (best < 0 || e < d2) best = static_cast<int>(k), d2 = e;
  }
  return best;
}

/// A traction or pressure as constant forces on the surface layer: the condition's length
/// (times the thickness) shared equally by the layer's particles, each with the preload's final
/// traction at its nearest boundary point.
void hold_force(HeldCondition& h, const spec::ProblemSpec& preload,
                const implicit::ConditionPoints& c, const Layer& l, double f, std::size_t mirrors) {
  h.kind = HeldCondition::Kind::Force;
  h.particles = l.particles;
  std::vector<int> every(c.points.x.size());
  double length = 0.0;
  for (std::size_t k = 0; k < every.size(); ++k) {
    every[k] = static_cast<int>(k);
    length += c.points.weight[k] * preload.thickness;
  }
  const std::vector<Vec2> traction = implicit::condition_values(preload, *c.bc, c.points, every);
  const double copies = static_cast<double>(1u << mirrors);
  const double share = copies * length / static_cast<double>(l.particles.size());
  for (std::size_t j = 0; j < l.particles.size(); ++j) {
    const int k = nearest_point(c.points, l.how[j].x.head<2>());
    const Vec2 t = k >= 0 ? Vec2(f * traction[k]) : Vec2::Zero();
    h.force.push_back(mirrored(Vec3(share * t.x(), share * t.y(), 0.0), l.how[j]));
  }
}

} // namespace

std::vector<HeldCondition> held_conditions(const spec::ProblemSpec& preload,
                                           const implicit::ElastoplasticResult& r,
                                           const spec::StageLink& link, const std::vector<Vec3>& x,
                                           const HoldLayers& layers) {
  const implicit::GalerkinModel& model = *r.state.model;
  const std::vector<double>& factor = r.state.factors;
  std::vector<HeldCondition> out;
  for (const std::string& name : link.hold) {
    HeldCondition h;
    h.name = name;
    if (name == "body_force" || name == "gravity") {
      h.kind = HeldCondition::Kind::Body;
      h.body_factor = factor.back();
      h.gravity = name == "gravity";
      out.push_back(h);
      continue;
    }
    const auto c =
        std::find_if(model.conditions.begin(), model.conditions.end(),
                     [&](const implicit::ConditionPoints& p) { return p.bc->name == name; });
    MF_REQUIRE(c != model.conditions.end(), link.key_path, ".hold: no condition '", name, "'");
    const spec::BoundaryCondition& bc = *c->bc;
    // The model's conditions are the spec's boundary conditions in their order.
    const double f = factor[static_cast<std::size_t>(c - model.conditions.begin())];
    const std::vector<geometry::Curve> pieces =
        spec::select_boundary(preload.domain, bc.on, bc.key_path);
    bool straight = true;
    const std::vector<Vec2> ends = segment_ends(pieces, straight);
    double scale = 1.0;
    for (const Vec2& p : ends) scale = std::max(scale, p.cwiseAbs().maxCoeff());
    const double tol = 1e-9 * scale;
    const bool both = bc.mask.x() > 0.0 && bc.mask.y() > 0.0;
    // A roller on a mirror plane is the mirror's own symmetry.
    if (!bc.loads && !both && on_mirror_plane(ends, straight, link.mirror, tol)) continue;
    const double depth = bc.loads ? layers.surface : layers.held;
    const Layer l = layer_of(x, pieces, link.mirror, depth);
    MF_REQUIRE(!l.particles.empty(), link.key_path, ".hold: no particle lies within ", depth,
               " of the boundary of condition '", name, "'");
    if (bc.loads) {
      hold_force(h, preload, *c, l, f, link.mirror.size());
      out.push_back(h);
      continue;
    }
    h.particles = l.particles;
    for (std::size_t j = 0; j < l.particles.size(); ++j)
      if (l.distance[j] < layers.surface) h.surface.push_back(l.particles[j]);
    if (both) {
      h.kind = HeldCondition::Kind::Clamp;
    } else {
      h.kind = HeldCondition::Kind::Roller;
      h.component = bc.mask.x() > 0.0 ? 0 : 1;
      h.value = f * bc.value[h.component];
      h.line = ends.empty() ? 0.0 : ends.front()[h.component];
      h.on_axis_line = straight && on_line(ends, h.component, h.line, tol);
    }
    out.push_back(h);
  }
  return out;
}

} // namespace mf::stages
