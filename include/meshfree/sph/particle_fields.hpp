#pragma once
// What SPH adds to each particle of the particle set (particles/particle_set.hpp): density,
// energy, smoothing length, the state the equations of state and strength models give, and the
// strength history. Arrays run over the set's particles, ghosts (mirror images) included.
#include <vector>

namespace mf::sph {

/// Per-particle SPH state (structure of arrays); tensors have 6 components per particle (Voigt:
/// xx yy zz yz xz xy).
struct ParticleFields {
  std::vector<double> rho, e, h;
  std::vector<double> h_ref;      // h = h_ref (rho_ref / rho)^(1/dim), rho_ref the set's density
  std::vector<double> light_time; // programmed burn: when the particle is lit (< 0: never burns)
  /// Fixed (wall) particles: they do not move, but their density and energy evolve, so that they
  /// push back on approaching particles (dynamic boundary particles, Crespo et al. 2007).
  std::vector<char> fixed;
  /// The velocity components a free particle keeps at zero (bit d: axis d), as a roller holds
  /// them: the other components move.
  std::vector<char> held_axes;
  std::vector<double> p, c;        // from the equation of state, per step
  std::vector<double> S;           // deviatoric stress
  std::vector<double> back_stress; // J2 kinematic hardening, like S
  std::vector<double> alpha;       // equivalent plastic strain
  std::vector<double> rho_max;     // largest density reached (compaction history)
  std::vector<double> damage;      // HJC damage, 0..1
  std::vector<double> strain_rate; // equivalent deviatoric strain rate sqrt(2/3 D':D') [1/s]
  std::vector<char> failed;        // no deviatoric stress and no tension once set
  /// Appends the state of a particle at rest with density rho, energy e and smoothing length h.
  void add(double rho, double e, double h, bool fixed);
  /// Appends a copy of particle i's state as a fixed particle (a mirror image starts as one).
  void append_copy(int i);
  /// Drops every particle from index n on.
  void truncate(int n);
  /// Calls visit(array, values per particle) for every array above: what a particle that moves
  /// to another rank takes with it.
  /// Every array by name (a checkpoint keeps them).
  template <class Visit> void for_each_state(Visit&& visit) {
    visit("rho", rho), visit("e", e), visit("h", h), visit("h_ref", h_ref);
    visit("light_time", light_time), visit("fixed", fixed), visit("held_axes", held_axes);
    visit("p", p), visit("c", c);
    visit("S", S), visit("back_stress", back_stress), visit("alpha", alpha);
    visit("rho_max", rho_max), visit("damage", damage), visit("strain_rate", strain_rate);
    visit("failed", failed);
  }
  template <class Visit> void for_each_array(Visit&& visit) {
    visit(rho, 1), visit(e, 1), visit(h, 1), visit(h_ref, 1), visit(light_time, 1);
    visit(fixed, 1), visit(held_axes, 1), visit(p, 1), visit(c, 1), visit(S, 6), visit(back_stress, 6);
    visit(alpha, 1), visit(rho_max, 1), visit(damage, 1), visit(strain_rate, 1);
    visit(failed, 1);
  }
};

} // namespace mf::sph
