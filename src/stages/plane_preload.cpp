// A plane preload as the explicit stage sees it (stages/preload.hpp).
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/stages/preload.hpp"

namespace mf::stages {

PreloadAtParticles PlanePreload::sample(const std::vector<Vec3>& x,
                                        const spec::StageLink& link) const {
  return sample_preload(spec(), r_, x, link.mirror, link.key_path);
}

std::vector<HeldCondition> PlanePreload::held(const spec::StageLink& link,
                                              const std::vector<Vec3>& x,
                                              const HoldLayers& layers) const {
  return held_conditions(spec(), r_, link, x, layers);
}

materials::IsotropicElastic PlanePreload::elasticity_at(const Vec3& x) const {
  return materials::elasticity(implicit::point_law(spec(), x.head<2>()).params);
}

Vec3 PlanePreload::body_force_at(bool gravity, const Vec3& x) const {
  const spec::GalerkinSpec& g = spec().galerkin();
  const Vec2 b =
      gravity
          ? Vec2(spec().materials[implicit::material_at(spec(), x.head<2>())].density * g.gravity)
          : g.body_force;
  return Vec3(b.x(), b.y(), 0.0);
}

Vec3 PlanePreload::gravity() const {
  const Vec2& g = spec().galerkin().gravity;
  return Vec3(g.x(), g.y(), 0.0);
}

} // namespace mf::stages
