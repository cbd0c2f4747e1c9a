#pragma once
// A peridynamic run as the explicit time loop drives it (explicit/time_loop.hpp): velocity-Verlet
// steps of a set-up body, a history row per recorded instant (energies and their balance, broken
// bonds, pd::damage, impactors, gauges, the crack tip), gauge maxima over every step, and fields
// (displacement, velocity, pd::damage, material).
#include "meshfree/explicit/gauges.hpp"
#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/pd/relaxation.hpp"
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mf::explicit_dynamics {

struct PdRunResult {
  int particles = 0; // over every rank
  long bonds = 0;    // counted once, over every rank
  int mpi_ranks = 1;
  long ghosts = 0, ghosts_largest = 0; // over every rank, and on the rank with the most
  long steps = 0;
  double dt = 0.0;
  std::string dt_limit;
  double bond_updates_per_second = 0.0; // directed bonds x steps / stepping seconds
  double bond_bytes_steady = 0.0;       // bytes per directed bond held by the bonds in a run
  double bond_bytes_peak = 0.0;         // ... and at most while they were built
  io::History history;
  double max_damage = 0.0;
  long broken_bonds = 0;
  /// max |E(t) - E(0) - W_ext - W_drive + D| / max(E, |W|) (pd_run.cpp: E with the contact and
  /// impactor energies, W_drive of prescribed impactors, D dissipated by kinematic contact).
  double energy_drift = 0.0;
  /// Largest |value| of every gauge component (u, v, a) over every step, not only the recorded
  /// ones: "<gauge>_<u|v|a><x|y|z>".
  std::vector<std::pair<std::string, double>> gauge_maxima;
  std::string status = "completed", stop_reason;
  std::optional<pd::RelaxReport> relaxation; // when the spec asks for one before the first step
  io::CheckpointCounts checkpoints;
  PhaseTimer timer;
};

class PdRun {
public:
  /// The body relaxed to static equilibrium under its loads at t = 0 when the spec asks for it
  /// (pd::relax; the initial velocities are kept), accelerations at t = 0 and the columns of the
  /// history; fields go to `out` (null: none). A relaxation that does not converge is an error.
  PdRun(PdSetup& setup, const spec::PdSpec& spec, io::OutputDirectory* out, PdRunResult& result);

  double time() const { return setup_.model.particles.time; }
  long step() const { return setup_.model.particles.step; }
  bool time_step(double remaining, double& dt, std::string&) const {
    dt = std::min(setup_.dt, remaining);
    return true;
  }
  void advance(double dt, bool history_due);
  void track() { gauges_.update_maxima(); }
  /// The lowest id of a particle whose motion is not finite, or -1. Collective.
  int nonfinite() const;
  /// The reference position of particle `id`. Collective.
  Vec3 position(int id) const;
  std::string advice() const;
  /// A load that alone moves a particle more than 10^6 spacings in one step, or is not finite:
  /// then the load, not the time step, made the motion non-finite ("" when none).
  std::string overflowing_load() const;
  void record();
  void write_fields();
  std::string progress() const { return detail::concat("broken bonds ", broken_ / 2); }
  /// The run's whole state into a checkpoint (the field steps so far split off into a part of
  /// it), and back on a restart.
  void save(io::Checkpoints& checkpoints, const io::Saver& save);
  void restore(const io::Loader& load);

  /// Counts, rates, status and energy balance of the finished loop into the result.
  void finish(const LoopReport& loop);

private:
  /// The body's counts (particles, bonds, ghosts, bytes per bond) and time step into the result.
  void count_body();
  /// The body relaxed to static equilibrium under its loads at t = 0, its velocities kept.
  void relax_at_start();
  /// Gauges of u, v and a in each of the body's axes, recorded and tracked.
  void gauge_motion();
  std::vector<std::string> history_columns() const;
  template <class Visit> void for_each_state(const Visit& visit);
  const distribution::Ranks& ranks() const { return setup_.model.halo.ranks(); }
  PdSetup& setup_;
  const spec::PdSpec& spec_;
  PdRunResult& r_;
  Gauges gauges_;
  io::FieldOutput fields_;
  /// The impactors, the short-range contact and, with contact, the fracture energy.
  pd::Interactions interactions() {
    pd::Interactions x;
    x.impactors = &setup_.impactors;
    x.short_range = setup_.short_range ? &*setup_.short_range : nullptr;
    x.fracture = contact_ ? &fracture_account_ : nullptr;
    return x;
  }
  /// Kinetic energy of the free impactors.
  double impactor_energy() const {
    double e = 0.0;
    for (const auto& imp : setup_.impactors) e += imp.kinetic_energy();
    return e;
  }

  pd::StepReport last_;   // of the last force evaluation
  bool contact_ = false;  // impactors or short-range contact: the balance has their energies
  double fracture_ = 0.0; // energy of the bonds broken so far (with contact)
  pd::FractureEnergy fracture_account_;
  bool last_has_energy_ = true;
  double e0_ = 0.0, work_ = 0.0;
  long broken_ = 0; // from both ends
  std::vector<double> phi_;
};

} // namespace mf::explicit_dynamics
