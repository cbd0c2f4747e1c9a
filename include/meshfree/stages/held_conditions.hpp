#pragma once
// The conditions of a preload as the particles of the next stage feel them when they are held.
// Which particles a condition acts on is decided by geometry alone: their distance to the
// condition's boundary pieces (its edges and arcs), never by the preload's quadrature, so the
// same particles are held whatever the preload's spacing.
// - A traction or pressure becomes constant forces on the surface layer (particles within one
//   spacing of its pieces): the condition's length is shared equally by the layer's particles,
//   each taking the preload's final traction at its nearest boundary point, so a uniform traction
//   on a straight edge gives every particle t x spacing and the total force carries over.
// - A displacement (a clamp, a grip, a roller with or without a value) holds every particle
//   within `held_depth` of its pieces at the preload's final displacement, in the components it
//   prescribes: the kernel's reach for SPH, the horizon for peridynamics, so that every particle
//   left free has its whole neighbourhood (or bond family) in the body, as the fixed/dummy
//   particle walls of SPH (Adami, Hu & Adams 2012) and the boundary layers one horizon deep of
//   peridynamics (Madenci & Oterkus 2014, ch. 2) give it. A truncated neighbourhood next to a
//   single held row would otherwise take the transferred stress as an unbalanced force.
// - A body force stays on.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/spec/problem_spec.hpp"
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
  std::vector<int> surface; // Clamp, Roller: the held particles within the surface layer
  double body_factor = 0.0; // Body: the preload's final body-force factor
  bool gravity = false;     // Body: gravity (rho g), else the uniform body force
};

/// How deep the particles a condition acts on reach into the body from its boundary pieces.
struct HoldLayers {
  double surface = 0.0; // a held force's layer: one particle spacing
  double held = 0.0;    // a held displacement's layer: the kernel's reach, or the horizon
};

/// The held conditions of `preload` (those `link.hold` names) on particles at reference positions
/// `x`, mirrored across `link.mirror`; a roller on a mirror plane is held by the mirror image and
/// yields nothing. Throws naming the condition if its layer holds no particle.
std::vector<HeldCondition> held_conditions(const spec::ProblemSpec& preload,
                                           const implicit::ElastoplasticResult& r,
                                           const spec::StageLink& link, const std::vector<Vec3>& x,
                                           const HoldLayers& layers);

} // namespace mf::stages
