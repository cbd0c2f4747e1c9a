#pragma once
// The particle arrays of an SPH run (structure of arrays).
#include <vector>

namespace mf::sph {

/// Particle arrays; vectors have 3 components per particle, the unused ones zero in 1D and 2D.
struct Particles {
  int dim = 3;
  std::vector<double> x, v;
  std::vector<double> mass, rho, e, h;
  std::vector<double> rho_ref, h_ref; // h = h_ref (rho_ref / rho)^(1/dim)
  std::vector<int> material;
  std::vector<double> light_time; // programmed burn: when the particle is lit (< 0: never burns)
  /// Fixed (wall) particles: they do not move, but their density and energy evolve, so that they
  /// push back on approaching particles (dynamic boundary particles, Crespo et al. 2007).
  std::vector<char> fixed;
  std::vector<double> p, c;        // from the equation of state, per step
  std::vector<double> S;           // deviatoric stress, 6 per particle: xx yy zz yz xz xy
  std::vector<double> back_stress; // J2 kinematic hardening, 6 per particle like S
  std::vector<double> alpha;       // equivalent plastic strain
  std::vector<double> rho_max;     // largest density reached (compaction history)
  std::vector<double> damage;      // HJC damage, 0..1
  std::vector<double> strain_rate; // equivalent deviatoric strain rate sqrt(2/3 D':D') [1/s]
  std::vector<char> failed;        // no deviatoric stress and no tension once set
  int size() const { return static_cast<int>(mass.size()); }
  /// Appends a copy of particle i (a mirror image starts as one).
  void append_copy(int i);
  /// Drops every particle from index n on.
  void truncate(int n);
  /// Appends a particle at rest.
  void add(const double position[3], double mass, double rho, double e, double h, int material,
           bool fixed = false);
};

} // namespace mf::sph
