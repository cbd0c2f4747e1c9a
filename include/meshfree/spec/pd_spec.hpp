#pragma once
// What the peridynamics part of a problem file says (analysis: peridynamics), validated and
// typed. Materials are the problem's `materials:` entries the body uses, each with its bond.
#include "meshfree/loads/time_function.hpp"
#include "meshfree/materials/pd_bonds.hpp"
#include "meshfree/spec/material_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

using Vec3d = Eigen::Vector3d;

/// Bonds between two materials: the law of `base` with its yield stretch times a factor (paper
/// 000: steel-concrete bonds have 3 times the concrete's yield stretch).
struct PdInterface {
  std::string a, b, base;
  double yield_stretch_factor = 1.0;
  double critical_stretch_factor = 1.0;
};

/// A part of the body with its own material (index into PdSpec::materials, -1: unchanged) and/or
/// initial velocity.
struct PdRegion {
  Region region;
  int material = -1;
  std::optional<Point> velocity;
};

struct PdCrack {
  Point a{0, 0, 0}, b{0, 0, 0}, c{0, 0, 0}; // segment a-b in a plane; parallelogram in 3D
};

struct PdFunction {
  std::string name;
  loads::TimeFunction f;
  int haar_level = 0;
  std::string file; // table source, for the summary
};

/// A constraint or a load on the particles of a region (or on all particles).
struct PdCondition {
  std::string name, key_path;
  std::optional<Region> region;
  enum class Kind { Displacement, Velocity, Traction, BodyForce, Blast } kind = Kind::Displacement;
  BlastSpec blast;
  bool fixed[3] = {false, false, false};
  Point value{0, 0, 0};
  double area = 0.0; // traction: loaded area (0: from the box)
  int function = -1;
};

struct PdImpactor {
  std::string name;
  bool sphere = true;
  double radius = 0.0;
  Point half_size{0, 0, 0};
  double mass = 0.0; // 0 for a fixed support or a prescribed motion
  bool fixed = false;
  bool prescribed = false; // moves at its velocity whatever the contact pushes
  bool penalty = false;    // contact.type: penalty (LAMMPS fix indent) rather than kinematic
  double stiffness = 0.0;  // penalty K; 0: derived (pd::derived_penalty_stiffness)
  Point position{0, 0, 0}, velocity{0, 0, 0};
};

struct PdCrackTracking {
  bool enabled = false;
  double threshold = 0.38;
  Point origin{0, 0, 0}, direction{0, 1, 0};
};

/// Adaptive dynamic relaxation of the body to static equilibrium under its loads at t = 0,
/// before the first step (pd::relax).
struct PdRelaxation {
  double tolerance = 1e-6;
  int max_iterations = 100000;
};

struct PdSpec {
  materials::PdDimension dimension = materials::PdDimension::Solid3D; // from model.type
  double thickness = 1.0;                                             // from model.thickness
  double spacing = 0.0;
  double horizon_factor = 3.0;             // delta = horizon_factor * spacing
  std::string volume_correction = "exact"; // exact | linear | none
  std::string surface_correction = "none"; // none | energy (bond-based) | position_aware (lps)
  bool short_range_contact = false; // LAMMPS peri/pmb's short-range repulsion of particles
  bool deterministic = false; // discretisation.deterministic: bonds in full rows, global-id order
  std::vector<MaterialSpec> materials; // each with density and bond
  int body_material = 0;
  std::vector<PdInterface> interfaces;
  std::vector<PdRegion> regions;
  std::vector<Region> removed; // notches
  std::vector<PdCrack> cracks;
  std::vector<PdFunction> functions;
  std::vector<PdCondition> conditions;
  std::vector<PdImpactor> impactors;
  double end_time = 0.0, dt = 0.0, safety = 0.8;
  SeriesOutputSpec output; // output: the history and field intervals, gauges, checkpoints
  PdCrackTracking crack;
  std::optional<PdRelaxation> relaxation;
  std::string key_prefix; // "stages[k]." for a stage of a staged run: its keys' path in messages

  /// Whether the body is state-based (its materials' bond law lps).
  bool state_based() const { return !materials.empty() && materials.front().bond->lps; }
  /// Whether a state-based body has elastic-plastic (eps) materials.
  bool state_plastic() const {
    for (const MaterialSpec& m : materials)
      if (m.bond && m.bond->lps && m.bond->yield_stress > 0.0) return true;
    return false;
  }
};

} // namespace mf::spec
