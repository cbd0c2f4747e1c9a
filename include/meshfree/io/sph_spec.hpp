#pragma once
// What an SPH problem file says (analysis: sph), validated and typed.
#include "meshfree/sph/hydro.hpp"
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace mf::io {

/// A circle in the x-y plane (a cylinder along z in 3D).
struct SphCircle {
  std::array<double, 3> center{0, 0, 0};
  double radius = 0.0;
};

/// A block of particles, one material, uniform initial state: a box on a lattice of the given
/// spacing, less any holes, or (2D) a ring of concentric particle circles.
struct SphBlock {
  std::string material;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0}; // unused axes: 0
  std::vector<SphCircle> holes;                   // particles inside are left out
  std::optional<SphCircle> inside;                // if given, only particles inside are kept
  bool is_ring = false;
  SphCircle ring; // center and outer radius
  double ring_inner_radius = 0.0;
  double spacing = 0.0;
  double density = 0.0;
  double energy = 0.0; // specific internal energy [J/kg]
  std::array<double, 3> velocity{0, 0, 0};
  bool fixed = false; // a wall of fixed particles
};

/// A Kingery-Bulmash blast on the particles of a box (a surface layer one particle thick).
struct SphBlastLoad {
  std::string name, key_path;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  double tnt_mass = 0.0;
  bool surface_burst = true;
  bool clamp_below_range = false; // closer than the fits reach: the values at their nearest end
  std::array<double, 3> charge{0, 0, 0}, normal{0, 0, 0}; // normal: unit, outward
};

/// A transmitting (Lysmer) boundary on the particles of a box, with its outward normal.
struct SphTransmitting {
  std::string name, key_path;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  std::array<double, 3> normal{0, 0, 0};
};

struct SphGauge {
  std::string name;
  std::array<double, 3> at{0, 0, 0};
};

struct SphSpec {
  int dimension = 1;      // 1, 2 (plane strain, per unit thickness) or 3
  double smoothing = 1.5; // h = smoothing * spacing
  std::vector<sph::Material> materials;
  std::vector<SphBlock> blocks;
  std::optional<std::array<double, 3>> detonation_point;  // a point, or with the normal a plane
  std::optional<std::array<double, 3>> detonation_normal; // unit
  sph::Settings settings;
  double end_time = 0.0;
  double history_interval = 0.0, fields_interval = 0.0; // 0: every step / start and end only
  std::vector<SphGauge> gauges;
  std::vector<SphBlastLoad> loads;
  std::vector<SphTransmitting> transmitting;
  std::vector<sph::SymmetryPlane> symmetry; // read from 'symmetry: [{axis: x, at: 0}]'
};

} // namespace mf::io
