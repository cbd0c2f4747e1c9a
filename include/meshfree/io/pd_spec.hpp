#pragma once
// What a peridynamics problem file says (analysis: peridynamics), validated and typed.
#include "meshfree/core/types.hpp"
#include "meshfree/loads/time_function.hpp"
#include "meshfree/materials/pd_bonds.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::io {

using Vec3d = Eigen::Vector3d;

struct Box3 {
  Vec3d lo{0, 0, 0}, hi{0, 0, 0};
  bool contains(const Vec3d& p, double tol) const {
    return (p - lo).minCoeff() >= -tol && (hi - p).minCoeff() >= -tol;
  }
};

struct PdMaterial {
  std::string name;
  double E = 0.0, density = 0.0;
  double bulk_modulus = 0.0;     // > 0: c = 18 k / (pi delta^4) (3D)
  double micromodulus = 0.0;     // > 0: c given directly
  double fracture_energy = 0.0;  // > 0: critical stretch from G0
  double critical_stretch = 0.0; // > 0: given directly
  double yield_stretch = 0.0;    // > 0: micro-plastic bond
  double alpha = 0.0;            // LAMMPS rule
};

/// Bonds between two materials: the law of `base` with its yield stretch times a factor (paper
/// 000: steel-concrete bonds have 3 times the concrete's yield stretch).
struct PdInterface {
  std::string a, b, base;
  double yield_stretch_factor = 1.0;
  double critical_stretch_factor = 1.0;
};

struct PdRegion {
  std::string material;
  Box3 box;
};

struct PdCrack {
  Vec3d a{0, 0, 0}, b{0, 0, 0}, c{0, 0, 0}; // segment a-b in a plane; parallelogram in 3D
};

struct PdFunction {
  std::string name;
  loads::TimeFunction f;
  int haar_level = 0;
  std::string file; // table source, for the summary
};

/// A TNT charge whose air blast loads a face (Kingery-Bulmash, loads/blast.hpp).
struct PdBlast {
  double tnt_mass = 0.0;     // kg of TNT (equivalent)
  bool surface_burst = true; // hemispherical surface burst, else spherical free air
  Vec3d charge{0, 0, 0};     // the charge's centre
  Vec3d normal{0, 0, 0};     // unit outward normal of the loaded face
};

/// A constraint or a load on the particles in a box (or on all particles).
struct PdCondition {
  std::string name, key_path;
  std::optional<Box3> box;
  enum class Kind { Displacement, Velocity, Traction, BodyForce, Blast } kind = Kind::Displacement;
  PdBlast blast;
  bool fixed[3] = {false, false, false};
  Vec3d value{0, 0, 0};
  double area = 0.0; // traction: loaded area (0: from the box)
  int function = -1;
};

struct PdImpactor {
  std::string name;
  bool sphere = true;
  double radius = 0.0;
  Vec3d half_size{0, 0, 0};
  double mass = 0.0; // 0 for a fixed support
  bool fixed = false;
  Vec3d position{0, 0, 0}, velocity{0, 0, 0};
};

struct PdGauge {
  std::string name;
  Vec3d at{0, 0, 0};
};

struct PdCrackTracking {
  bool enabled = false;
  double threshold = 0.38;
  Vec3d origin{0, 0, 0}, direction{0, 1, 0};
};

struct PdSpec {
  materials::PdDimension dimension = materials::PdDimension::Solid3D;
  double thickness = 1.0;
  std::optional<Box3> box; // 3D body (2D bodies use ProblemSpec::domain)
  double spacing = 0.0;
  double horizon_factor = 3.0;             // delta = horizon_factor * spacing
  std::string volume_correction = "exact"; // exact | linear | none
  bool surface_correction = false;
  std::vector<PdMaterial> materials;
  std::vector<PdInterface> interfaces;
  std::vector<PdRegion> regions;
  std::vector<Box3> removed;
  std::vector<PdCrack> cracks;
  struct InitialVelocity {
    std::optional<Box3> box; // none: every particle
    Vec3d value{0, 0, 0};
  };
  std::vector<InitialVelocity> initial_velocities;
  std::vector<PdFunction> functions;
  std::vector<PdCondition> conditions;
  std::vector<PdImpactor> impactors;
  double end_time = 0.0, dt = 0.0, safety = 0.8;
  double history_interval = 0.0, fields_interval = 0.0; // 0: every step / only the end
  std::vector<PdGauge> gauges;
  PdCrackTracking crack;
};

} // namespace mf::io
