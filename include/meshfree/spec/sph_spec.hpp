#pragma once
// What the SPH part of a problem file says (analysis: sph), validated and typed: plain data that
// the SPH builder maps to the solver's own settings.
#include "meshfree/kernels/sph_kernel.hpp"
#include "meshfree/materials/geomaterials.hpp"
#include "meshfree/spec/material_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include "meshfree/sph/settings.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

/// Bounds on a particle's smoothing length as multiples of its initial one, as LS-DYNA's HMIN
/// and HMAX scale factors: h = smoothing x spacing at the start, and h follows rho^(-1/dim)
/// within [min, max] times that, the density being held within the bounds this gives it.
/// The defaults are LS-DYNA's, 0.2 and 2 (a volume 8 times the initial in 3D, 4 in 2D), but for
/// max in 1D, where h grows as the volume itself: 3 there, since the rarefaction of Sod's tube
/// alone expands the gas 2.35 times.
struct SmoothingBounds {
  double min = 0.2, max = 2.0;
  static SmoothingBounds defaults(int dimension) { return {0.2, dimension == 1 ? 3.0 : 2.0}; }
};

/// A body of particles, one material, uniform initial state: a box on a lattice of the given
/// spacing (kept inside the region's circle, less its holes), or (2D) a ring of concentric
/// particle circles.
struct SphRegion {
  int material = 0; // index into SphSpec::materials
  Region region;
  double spacing = 0.0;
  double density = 0.0;
  double energy = 0.0; // specific internal energy [J/kg]
  Point velocity{0, 0, 0};
  /// A velocity that varies along an axis, added to `velocity`: component `component` is
  /// table(x_along) (piecewise linear, constant beyond its ends); a beam's mode shape, say.
  struct VelocityProfile {
    int along = 0, component = 1;
    materials::PiecewiseLinear table;
  };
  std::optional<VelocityProfile> velocity_profile;
  bool fixed = false;    // a wall of fixed particles
  std::string key_path;  // "regions[k]", for messages
  std::string state_key; // the key that gave its state: pressure, energy or density
  /// Its particles' h is held within these multiples of their initial h (SphSpec's).
  SmoothingBounds smoothing_bounds;
};

/// A Kingery-Bulmash blast on the particles of a region (a surface layer one particle thick).
struct SphBlastLoad {
  std::string name, key_path;
  Region region;
  BlastSpec blast;
};

/// A transmitting (Lysmer) boundary on the particles of a region, with its outward normal.
struct SphTransmitting {
  std::string name, key_path;
  Region region;
  Point normal{0, 0, 0};
};

/// A constant traction (force per area) on the particles of a region (a surface layer one
/// particle thick), each taking it times its face area.
struct SphTraction {
  std::string name, key_path;
  Region region;
  Point traction{0, 0, 0};
};

/// A mirror plane normal to a coordinate axis.
struct SphSymmetry {
  std::string name;
  int axis = 0;
  double at = 0.0;
};

struct SphSpec {
  int dimension = 1;      // 1 (uniaxial strain), 2 (plane strain, per unit thickness) or 3
  double smoothing = 1.5; // h = smoothing * spacing
  SmoothingBounds smoothing_bounds;    // every region's, unless it gives its own
  std::vector<MaterialSpec> materials; // each with an equation of state
  std::vector<SphRegion> regions;
  std::optional<Point> detonation_point;  // a point, or with the normal a plane
  std::optional<Point> detonation_normal; // unit
  sph::Settings numerics; // the solver's own parameters (the neighbour-list skin is not read)
  double end_time = 0.0;
  SeriesOutputSpec output; // output: the history and field intervals, gauges, checkpoints
  std::vector<SphBlastLoad> loads;
  std::vector<SphTransmitting> transmitting;
  std::vector<SphTraction> tractions;
  std::vector<SphSymmetry> symmetry;
  Point gravity{0, 0, 0}; // body acceleration on every free particle
  std::string key_prefix; // "stages[k]." for a stage of a staged run: its keys' path in messages
};

} // namespace mf::spec
