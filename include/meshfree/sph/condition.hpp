#pragma once
// Boundary conditions of an SPH run as objects of one interface, in the manner of [LAMMPS]'s fixes
// (a `post_force` hook per fix, called once per step in the fixes' order) and [MFEM]'s integrators
// (one object per term, a list that the assembly loops over): the step and the distribution over
// ranks call the hooks of every condition in the run's list without knowing its kind. A hook is
// called once per condition per evaluation; what it does per particle is a loop over its own
// flat arrays. The kinds are in sph/surface_load.hpp, sph/surface_force.hpp and
// sph/transmitting_boundary.hpp.
//
// Body-level settings are not conditions: gravity and mass-proportional damping act on every
// free particle inside the pair sums' own loop (sph::BodyForces); fixed particles and held
// components are per-particle fields that migrate with their particle (sph::ParticleFields);
// symmetry planes make mirror particles, part of the ghost layer (sph/symmetry.hpp).
#include "meshfree/particles/particle_set.hpp"
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace mf::sph {

struct Hydro;

/// What a condition's checkpointed state is visited through: the checkpoint's visitors are
/// templates, which a virtual hook cannot take, so each is wrapped in this (StateVisitorOf).
class StateVisitor {
public:
  virtual ~StateVisitor() = default;
  virtual void operator()(const std::string& name, double& v) const = 0;
  virtual void operator()(const std::string& name, long& v) const = 0;
  virtual void operator()(const std::string& name, std::vector<double>& v) const = 0;
  virtual void operator()(const std::string& name, std::vector<int>& v) const = 0;
};

template <class Visit> class StateVisitorOf final : public StateVisitor {
public:
  explicit StateVisitorOf(Visit visit) : visit_(std::move(visit)) {}
  void operator()(const std::string& name, double& v) const override { visit_(name, v); }
  void operator()(const std::string& name, long& v) const override { visit_(name, v); }
  void operator()(const std::string& name, std::vector<double>& v) const override {
    visit_(name, v);
  }
  void operator()(const std::string& name, std::vector<int>& v) const override { visit_(name, v); }

private:
  Visit visit_;
};

/// A boundary condition on a set of particles (local indices on a rank, global ids in the whole
/// body's list a rank cuts its own from).
class Condition {
public:
  virtual ~Condition() = default;
  virtual std::unique_ptr<Condition> clone() const = 0;
  virtual const std::string& label() const = 0;
  /// The place of the condition's kind in the sum of forces on a particle (Conditions keeps the
  /// list in this order, conditions of one kind in the order they were added), so that the sum
  /// does not depend on the order in which a run's set-up adds conditions.
  virtual int order() const = 0;
  /// Adds the condition's accelerations at time t to dv (3 per particle) of the particles it
  /// acts on (post_force).
  virtual void add_accelerations(const Hydro& s, double t, std::vector<double>& dv) const = 0;
  /// Appends the condition's forces at time t, particle by particle, to who and force (3 per
  /// entry): the step takes their work from these.
  virtual void append_forces(const Hydro& s, double t, std::vector<int>& who,
                             std::vector<double>& force) const = 0;
  /// This rank's part of the whole body's condition (particles by global id): its entries on
  /// the rank's owned particles, renumbered to their local indices, in the whole's order.
  virtual std::unique_ptr<Condition> owned_part(const particles::ParticleSet& P) const = 0;
  /// The largest constant force it holds on one particle (0 for a load that varies in time):
  /// the scale against which a body held at rest measures what is left out of balance.
  virtual double largest_held_force() const { return 0.0; }
  /// Whether it is a load of the event itself (a pressure history from t = 0), set aside while
  /// a staged run settles under its held loads.
  virtual bool part_of_event() const { return false; }
  /// Visits the state that changes as the run goes and a checkpoint keeps (none by default).
  virtual void for_each_state(const StateVisitor&) {}
};

/// The entries of a condition's particle list that this rank owns (particles by global id) and
/// their local indices, in the list's order.
struct OwnedEntries {
  std::vector<std::size_t> entries;
  std::vector<int> local;
};
OwnedEntries owned_entries(const particles::ParticleSet& P, const std::vector<int>& ids);

/// The values of `entries` of a per-entry array, `per` values an entry.
template <class T>
std::vector<T> pick(const std::vector<T>& a, const std::vector<std::size_t>& entries,
                    std::size_t per = 1) {
  std::vector<T> out;
  out.reserve(entries.size() * per);
  for (const std::size_t k : entries) out.insert(out.end(), &a[per * k], &a[per * k] + per);
  return out;
}

/// A run's list of conditions, in the order of Condition::order, copied condition by condition;
/// over several ranks also the whole body's list each rank cuts its own part from.
class Conditions {
public:
  Conditions() = default;
  Conditions(const Conditions& other);
  Conditions& operator=(const Conditions& other);
  Conditions(Conditions&&) = default;
  Conditions& operator=(Conditions&&) = default;

  /// Adds a condition after those of its kind and the kinds before it; returns it.
  template <class Kind> Kind& add(Kind c) {
    static_assert(std::is_base_of_v<Condition, Kind>, "a kind of sph::Condition");
    return static_cast<Kind&>(insert(std::make_unique<Kind>(std::move(c))));
  }
  std::size_t size() const { return list_.size(); }
  bool empty() const { return list_.empty(); }
  Condition& operator[](std::size_t k) { return *list_[k]; }
  const Condition& operator[](std::size_t k) const { return *list_[k]; }
  /// The conditions of one kind, in the list's order.
  template <class Kind> std::vector<Kind*> of_kind() {
    std::vector<Kind*> out;
    for (const auto& c : list_)
      if (auto* k = dynamic_cast<Kind*>(c.get())) out.push_back(k);
    return out;
  }
  template <class Kind> std::vector<const Kind*> of_kind() const {
    std::vector<const Kind*> out;
    for (const auto& c : list_)
      if (const auto* k = dynamic_cast<const Kind*>(c.get())) out.push_back(k);
    return out;
  }
  /// Removes the loads of the event (Condition::part_of_event) and returns them.
  Conditions take_event_loads();
  /// Adds every condition of `other`.
  void add_all(Conditions&& other);

  /// Keeps the list as the whole body's (particles by global id) and cuts this rank's part.
  void keep_whole(const particles::ParticleSet& P);
  /// Cuts this rank's part of the whole body's list again for its owned particles (nothing when
  /// no whole list is kept: one rank).
  void cut(const particles::ParticleSet& P);

  /// Visits each condition's checkpointed state under its label.
  template <class Visit> void for_each_state(Visit&& visit) {
    for (const auto& c : list_) c->for_each_state(StateVisitorOf(visit / c->label()));
  }

private:
  Condition& insert(std::unique_ptr<Condition> c);
  std::vector<std::unique_ptr<Condition>> list_;
  std::vector<std::unique_ptr<Condition>> whole_;
};

} // namespace mf::sph
