#pragma once
// What SPH adds to each particle of the particle set (particles/particle_set.hpp): density,
// energy, smoothing length, the state the equations of state and strength models give, and the
// strength history. Arrays run over the set's particles, ghosts (mirror images) included.
#include "meshfree/particles/field_info.hpp"
#include <vector>

namespace mf::sph {

/// Per-particle SPH state (structure of arrays); tensors have 6 components per particle (Voigt:
/// xx yy zz yz xz xy).
struct ParticleFields {
  std::vector<double> rho, e, h;
  std::vector<double> h_ref;      // h = h_ref (rho_ref / rho)^(1/dim), rho_ref the set's density
  /// The density is held within [rho_lo, rho_hi] (sph::advance), and so h within the bounds
  /// they give (spec::SmoothingBounds): a particle whose neighbours recede would otherwise expand
  /// without limit, and its h with it, until it pairs with the whole body.
  std::vector<double> rho_lo, rho_hi;
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
  /// Appends the state of a particle at rest with density rho, energy e and smoothing length h
  /// (its density unbounded: rho_lo 0, rho_hi infinite).
  void add(double rho, double e, double h, bool fixed);
  /// Appends a copy of particle i's state as a fixed particle (a mirror image starts as one).
  void append_copy(int i);
  /// Drops every particle from index n on.
  void truncate(int n);
  /// The registry of SPH's per-particle arrays (particles/field_info.hpp): calls
  /// visit(info, &ParticleFields::array) once per array. A new per-particle array is added here.
  template <class Visit> static constexpr void for_each_member(Visit&& visit) {
    using namespace particles;
    constexpr unsigned kept = kMigrates | kCheckpointed, set_up = kept | kSetUp;
    visit(FieldInfo{"rho", 1, kept, "density"}, &ParticleFields::rho);
    visit(FieldInfo{"e", 1, kept, "specific_energy"}, &ParticleFields::e);
    visit(FieldInfo{"h", 1, kept, "smoothing_length"}, &ParticleFields::h);
    visit(FieldInfo{"h_ref", 1, set_up}, &ParticleFields::h_ref);
    visit(FieldInfo{"rho_lo", 1, set_up}, &ParticleFields::rho_lo);
    visit(FieldInfo{"rho_hi", 1, set_up}, &ParticleFields::rho_hi);
    visit(FieldInfo{"light_time", 1, kept}, &ParticleFields::light_time);
    visit(FieldInfo{"fixed", 1, set_up}, &ParticleFields::fixed);
    visit(FieldInfo{"held_axes", 1, set_up}, &ParticleFields::held_axes);
    visit(FieldInfo{"p", 1, kept, "pressure"}, &ParticleFields::p);
    visit(FieldInfo{"c", 1, kept}, &ParticleFields::c);
    visit(FieldInfo{"S", 6, kept}, &ParticleFields::S);
    visit(FieldInfo{"back_stress", 6, kept}, &ParticleFields::back_stress);
    visit(FieldInfo{"alpha", 1, kept, "plastic_strain"}, &ParticleFields::alpha);
    visit(FieldInfo{"rho_max", 1, kept}, &ParticleFields::rho_max);
    visit(FieldInfo{"damage", 1, kept, "damage"}, &ParticleFields::damage);
    visit(FieldInfo{"strain_rate", 1, kept}, &ParticleFields::strain_rate);
    visit(FieldInfo{"failed", 1, kept, "failed"}, &ParticleFields::failed);
  }
  /// Calls visit(info, array) for every array, in the registry's order.
  template <class Visit> void for_each_field(Visit&& visit) {
    for_each_member([this, &visit](const particles::FieldInfo& f, auto m) { visit(f, this->*m); });
  }
  template <class Visit> void for_each_field(Visit&& visit) const {
    for_each_member([this, &visit](const particles::FieldInfo& f, auto m) { visit(f, this->*m); });
  }
  /// What a checkpoint keeps: every checkpointed array by name.
  template <class Visit> void for_each_state(Visit&& visit) {
    particles::for_each_kept(*this, visit);
  }
};

} // namespace mf::sph
