#pragma once
// One particle set for every particle method (peridynamics, SPH): the reference configuration
// (position X, volume, density, mass, material, the body each particle was generated in), the
// kinematics (displacement u, velocity v, acceleration a; the current position is X + u) and the
// instant they describe. Arrays are flat, 3 values per particle for vectors (unused axes 0), so
// that hot loops index them directly. Owned particles come first; ghost particles (mirror images,
// copies of a neighbour's particles) follow them, so loops say which they mean with owned() or
// all() instead of remembering a count. What a model adds per particle lives beside the set in
// its own arrays (composition, as CabanaPD's base particles and model layers), kept as committed
// and trial values where a step may be redone (Peridigm's STEP_N and STEP_NP1).
#include "meshfree/core/types.hpp"
#include "meshfree/particles/field_info.hpp"
#include <vector>

namespace mf::particles {

/// The indices [begin, end) of a part of a particle set, for range-for loops.
class Range {
public:
  class iterator {
  public:
    explicit iterator(int i) : i_(i) {}
    int operator*() const { return i_; }
    iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator!=(const iterator& o) const { return i_ != o.i_; }

  private:
    int i_;
  };
  Range(int begin, int end) : begin_(begin), end_(end) {}
  iterator begin() const { return iterator(begin_); }
  iterator end() const { return iterator(end_); }
  int first() const { return begin_; }
  int size() const { return end_ - begin_; }

private:
  int begin_, end_;
};

/// A per-particle quantity at the last accepted step (committed) and at the step being taken
/// (trial); commit() makes the trial values the committed ones.
template <class T> struct Staged {
  std::vector<T> committed, trial;
  void assign(std::size_t n, const T& value) {
    committed.assign(n, value);
    trial.assign(n, value);
  }
  bool empty() const { return committed.empty(); }
  void commit() { committed.swap(trial); }
};

struct ParticleSet {
  std::vector<double> X;       // reference positions
  std::vector<double> volume;  // reference volume (2D: area times thickness)
  std::vector<double> density; // reference density
  std::vector<double> mass;    // density times volume
  std::vector<int> material;   // index into the analysis' materials
  std::vector<int> body;       // the block or region the particle was generated in
  std::vector<long> id;        // global id: the index in the whole body, whichever rank holds it
  std::vector<double> u, v, a; // displacement, velocity, acceleration
  double time = 0.0;           // the instant of u, v and a
  long step = 0;

  int size() const { return static_cast<int>(volume.size()); }
  int owned_count() const { return owned_ < 0 ? size() : owned_; }
  Range owned() const { return {0, owned_count()}; }
  Range ghosts() const { return {owned_count(), size()}; }
  Range all() const { return {0, size()}; }
  Vec3 reference(int i) const { return {X[3 * i], X[3 * i + 1], X[3 * i + 2]}; }
  Vec3 position(int i) const {
    return {X[3 * i] + u[3 * i], X[3 * i + 1] + u[3 * i + 1], X[3 * i + 2] + u[3 * i + 2]};
  }

  /// Appends an owned particle at rest with the next global id; there must be no ghost yet.
  /// Returns its index.
  int add(const Vec3& x, double volume, double density, int material, int body = 0);
  /// Appends a ghost particle, a copy of particle `source` (the caller mirrors or moves it).
  int add_ghost(int source) { return add_ghost(*this, source); }
  /// Appends a ghost particle, a copy of particle `source` of `from` (this set or the whole body
  /// another rank owns a part of), id included.
  int add_ghost(const ParticleSet& from, int source) {
    begin_ghosts();
    return add_copy(from, source);
  }
  /// Appends a copy of particle `source` of `from` (every registered array, id included): an
  /// owned particle until the ghosts begin, a ghost after. Returns its index.
  int add_copy(const ParticleSet& from, int source);
  /// Removes every ghost particle.
  void drop_ghosts();
  /// Removes the ghost particles from index `first` on (first >= owned_count()).
  void drop_ghosts_from(int first);
  /// Particles appended from now on (by whoever fills the arrays: a rank's received copies) are
  /// ghosts.
  void begin_ghosts() {
    if (owned_ < 0) owned_ = size();
  }
  /// The registry of the set's per-particle arrays (particles/field_info.hpp): calls
  /// visit(info, &ParticleSet::array) once per array. A new per-particle array is added here.
  template <class Visit> static constexpr void for_each_member(Visit&& visit) {
    constexpr unsigned kept = kMigrates | kCheckpointed, reference = kept | kSetUp;
    visit(FieldInfo{"X", 3, reference}, &ParticleSet::X);
    visit(FieldInfo{"volume", 1, reference}, &ParticleSet::volume);
    visit(FieldInfo{"density", 1, reference}, &ParticleSet::density);
    visit(FieldInfo{"mass", 1, reference}, &ParticleSet::mass);
    visit(FieldInfo{"material", 1, reference, "material"}, &ParticleSet::material);
    visit(FieldInfo{"body", 1, reference}, &ParticleSet::body);
    visit(FieldInfo{"id", 1, reference}, &ParticleSet::id);
    visit(FieldInfo{"u", 3, kept, "displacement"}, &ParticleSet::u);
    visit(FieldInfo{"v", 3, kept, "velocity"}, &ParticleSet::v);
    visit(FieldInfo{"a", 3, kept}, &ParticleSet::a);
  }
  /// Calls visit(info, array) for every per-particle array, in the registry's order.
  template <class Visit> void for_each_field(Visit&& visit) {
    for_each_member([this, &visit](const FieldInfo& f, auto m) { visit(f, this->*m); });
  }
  template <class Visit> void for_each_field(Visit&& visit) const {
    for_each_member([this, &visit](const FieldInfo& f, auto m) { visit(f, this->*m); });
  }
  /// The set's own numbers: the instant, the step and where the ghosts begin.
  template <class Visit> void for_each_scalar(Visit&& visit) {
    visit("time", time), visit("step", step), visit("owned", owned_);
  }
  /// What a checkpoint keeps: every checkpointed array by name, then the set's numbers.
  template <class Visit> void for_each_state(Visit&& visit) {
    for_each_kept(*this, visit);
    for_each_scalar(visit);
  }

private:
  int owned_ = -1; // -1: no ghost particle, every particle is owned
};

} // namespace mf::particles
