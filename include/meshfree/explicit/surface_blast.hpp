#pragma once
// A TNT charge's air blast on a surface layer of particles: each particle gets the Friedlander
// pressure history of its own distance to the charge and angle of incidence (loads/blast.hpp), so
// that a face near the charge sees the earlier, higher and shorter pulse.
#include "meshfree/core/types.hpp"
#include "meshfree/loads/blast.hpp"
#include <string>
#include <vector>

namespace mf::explicit_dynamics {

struct Charge {
  double tnt_mass = 0.0;          // kg of TNT (equivalent)
  bool surface_burst = true;      // hemispherical surface burst, else spherical free air
  bool clamp_below_range = false; // nearer than the fits reach: the values at their nearest end
  Vec3 center{0, 0, 0};
  Vec3 normal{0, 0, 0}; // unit outward normal of the loaded face
};

/// The pulse of every listed particle (positions x, y, z per particle). A particle nearer the
/// charge than the fits reach is an error naming `key_path` and the particle, unless
/// clamp_below_range takes the values at the smallest scaled distance the fits cover there (the
/// crater region is not modelled).
std::vector<loads::Friedlander> surface_pulses(const Charge& charge,
                                               const std::vector<double>& positions,
                                               const std::vector<int>& particles,
                                               const std::string& key_path);

} // namespace mf::explicit_dynamics
