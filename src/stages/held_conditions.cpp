#include "meshfree/stages/held_conditions.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include <algorithm>
#include <cmath>

namespace mf::stages {

namespace {

/// Every image of a point of the part across the mirror planes (the point itself first), with
/// the reflections that made it.
std::vector<std::pair<Vec3, Mirrored>> images(const Vec2& p,
                                              const std::vector<io::MirrorPlane>& mirror) {
  std::vector<std::pair<Vec3, Mirrored>> out{{Vec3(p.x(), p.y(), 0.0), Mirrored{p, {}}}};
  for (const io::MirrorPlane& m : mirror) {
    const std::size_t n = out.size();
    for (std::size_t k = 0; k < n; ++k) {
      auto [y, how] = out[k];
      y[m.axis] = 2.0 * m.at - y[m.axis];
      how.flip[m.axis] = !how.flip[m.axis];
      out.emplace_back(y, how);
    }
  }
  return out;
}

bool on_mirror_plane(const std::vector<Vec2>& pts, const std::vector<io::MirrorPlane>& mirror,
                     double tol) {
  for (const io::MirrorPlane& m : mirror) {
    bool all = !pts.empty() && m.axis < 2;
    for (const Vec2& p : pts) all = all && std::abs(p[m.axis] - m.at) <= tol;
    if (all) return true;
  }
  return false;
}

/// The particles within `layer` of any image of the points, each with the index of the point
/// (and image) nearest to it.
struct Layer {
  std::vector<int> particles, point;
  std::vector<Mirrored> how;
};

Layer layer_of(const std::vector<Vec3>& x, const std::vector<Vec2>& pts,
               const std::vector<io::MirrorPlane>& mirror, double layer) {
  std::vector<double> d2(x.size(), layer * layer);
  std::vector<int> point(x.size(), -1);
  std::vector<Mirrored> how(x.size());
  for (std::size_t k = 0; k < pts.size(); ++k)
    for (const auto& [y, m] : images(pts[k], mirror))
      for (std::size_t i = 0; i < x.size(); ++i) {
        const double e = (x[i] - y).squaredNorm();
        if (e <= d2[i]) d2[i] = e, point[i] = static_cast<int>(k), how[i] = m;
      }
  Layer l;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (point[i] >= 0)
      l.particles.push_back(static_cast<int>(i)), l.point.push_back(point[i]),
          l.how.push_back(how[i]);
  return l;
}

} // namespace

std::vector<HeldCondition> held_conditions(const io::ProblemSpec& preload,
                                           const implicit::ElastoplasticResult& r,
                                           const io::StageLink& link, const std::vector<Vec3>& x,
                                           double layer) {
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
    const io::BoundaryCondition& bc = *c->bc;
    const double f = factor[static_cast<std::size_t>(&bc - preload.boundary.data())];
    std::vector<Vec2> pts;
    for (int row : c->mine.rows) pts.push_back(c->points.x[row]);
    double scale = 0.0, length = 0.0;
    for (const Vec2& p : pts) scale = std::max(scale, p.cwiseAbs().maxCoeff());
    for (double w : c->weight) length += w;
    const double tol = 1e-9 * std::max(scale, 1.0);
    const bool both = bc.mask.x() > 0.0 && bc.mask.y() > 0.0;
    // A roller on a mirror plane is the mirror's own symmetry.
    if (!bc.loads && !both && on_mirror_plane(pts, link.mirror, tol)) continue;
    const Layer l = layer_of(x, pts, link.mirror, layer);
    MF_REQUIRE(!l.particles.empty(), link.key_path, ".hold: no particle lies within ", layer,
               " of the boundary of condition '", name, "'");
    h.particles = l.particles;
    if (bc.loads) {
      h.kind = HeldCondition::Kind::Force;
      const double copies = static_cast<double>(1u << link.mirror.size());
      const double share = copies * length / static_cast<double>(l.particles.size());
      for (std::size_t j = 0; j < l.particles.size(); ++j) {
        const Vec2 t = f * c->values[l.point[j]];
        h.force.push_back(mirrored(Vec3(share * t.x(), share * t.y(), 0.0), l.how[j]));
      }
    } else if (both) {
      h.kind = HeldCondition::Kind::Clamp;
    } else {
      h.kind = HeldCondition::Kind::Roller;
      h.component = bc.mask.x() > 0.0 ? 0 : 1;
      h.value = f * bc.value[h.component];
      h.on_axis_line = true;
      h.line = pts.front()[h.component];
      for (const Vec2& p : pts)
        h.on_axis_line = h.on_axis_line && std::abs(p[h.component] - h.line) <= tol;
    }
    out.push_back(h);
  }
  return out;
}

} // namespace mf::stages
