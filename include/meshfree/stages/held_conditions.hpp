#pragma once
// The conditions of a preload as the particles of the next stage feel them when they are held.
// A condition acts on the surface layer of particles along its boundary: those within `layer`
// (about one particle spacing) of one of its boundary Gauss points. A traction or pressure
// becomes constant forces on that layer: the condition's length (its Gauss weights) is shared
// equally by the layer's particles, each taking the preload's final traction at its nearest
// boundary point, so a uniform traction on a straight edge gives every particle t x spacing and
// the total force carries over. A clamp fixes the layer, a roller (one component) holds that
// component, and a body force stays on.
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
  double value = 0.0;       // Roller: the prescribed displacement at the final factor
  double body_factor = 0.0; // Body: the preload's final body-force factor
  bool gravity = false;     // Body: gravity (rho g), else the uniform body force
};

/// The held conditions of `preload` (those `link.hold` names) on particles at reference positions
/// `x`, mirrored across `link.mirror`; a roller on a mirror plane is held by the mirror image and
/// yields nothing. Throws naming the condition if its layer holds no particle.
std::vector<HeldCondition> held_conditions(const io::ProblemSpec& preload,
                                           const implicit::ElastoplasticResult& r,
                                           const io::StageLink& link, const std::vector<Vec3>& x,
                                           double layer);

} // namespace mf::stages
