#pragma once
// The conditions of a preload as the particles of the next stage feel them when they are held:
// a traction or pressure becomes constant forces on the particles nearest its boundary points
// (the force of each boundary Gauss point at the preload's final factor, so the total force and
// its distribution carry over), a clamp fixes the particles nearest its boundary, a roller
// (one component) holds that component, and a body force stays on.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/problem_spec.hpp"
#include <string>
#include <vector>

namespace mf::stages {

struct HeldCondition {
  enum class Kind { Force, Clamp, Roller, Body };
  std::string name;
  Kind kind = Kind::Force;
  std::vector<int> particles; // Force, Clamp, Roller: the particles it acts on
  std::vector<Vec3> force;    // Force: per particle
  int component = -1;         // Roller: the component held
  bool on_axis_line = false;  // Roller: its boundary is the straight line x_component = line
  double line = 0.0;
  double value = 0.0;             // Roller: the prescribed displacement at the final factor
  Vec3 body_force = Vec3::Zero(); // Body: force per volume at the final factor
};

/// The held conditions of `preload` (those `link.hold` names) on particles at reference positions
/// `x`, mirrored across `link.mirror`; a roller on a mirror plane is held by the mirror image and
/// yields nothing.
std::vector<HeldCondition> held_conditions(const io::ProblemSpec& preload,
                                           const implicit::ElastoplasticResult& r,
                                           const io::StageLink& link, const std::vector<Vec3>& x);

} // namespace mf::stages
