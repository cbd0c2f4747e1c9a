#pragma once
// An SPH run as the explicit time loop drives it (explicit/time_loop.hpp): CFL-limited midpoint
// steps of a built body, a history row per recorded instant (sph::energies and their balance, peak
// pressure, gauges), gauge maxima over every step, and fields of the body's particles.
#include "meshfree/core/timer.hpp"
#include "meshfree/explicit/gauges.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/spec/sph_spec.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/step.hpp"
#include <string>
#include <utility>
#include <vector>

namespace mf::explicit_dynamics {

struct SphRunResult {
  int particles = 0; // over every rank
  int mpi_ranks = 1;
  long remote_ghosts = 0, remote_ghosts_largest = 0; // at the last list build: all, fullest rank
  long migrated = 0; // particles that moved to another rank over the run
  sph::SmoothingBoundHits bounded_h; // particle-steps with h held at a bound, every rank's
  long steps = 0;
  int neighbour_rebuilds = 0;
  double neighbour_seconds = 0.0; // of the stepping time, in neighbour checks and builds
  long neighbour_pairs = 0;       // directed pairs in the last neighbour lists of every rank
  long neighbour_list_bytes = 0;  // their size: partners and row offsets
  double first_dt = 0.0, smallest_dt = 0.0;
  std::string dt_limit; // the particle that set the smallest step
  double particle_steps_per_second = 0.0;
  double peak_pressure = 0.0, energy_error = 0.0; // |E(t) - E(0) - W| / scale, largest
  io::History history;
  /// Largest |pressure| and speed of every gauge over every step: "<gauge>_<pressure|speed>".
  std::vector<std::pair<std::string, double>> gauge_maxima;
  std::string status = "completed", stop_reason;
  io::CheckpointCounts checkpoints;
  PhaseTimer timer;
};

class SphRun {
public:
  /// The history's columns and the gauges of the body `h` at t = 0; fields go to `out` (null:
  /// none; on more than one rank: the ranks without it). Every call below is collective over the
  /// ranks the body is spread over (sph/decomposition.hpp).
  SphRun(sph::Hydro& h, const spec::SphSpec& spec, io::OutputDirectory* out, SphRunResult& result);

  double time() const { return h_.particles.time; }
  long step() const { return h_.particles.step; }
  bool time_step(double remaining, double& dt, std::string& why);
  void advance(double dt, bool);
  void track();
  /// The lowest global id of a particle whose motion is not finite, or -1.
  int nonfinite() const;
  /// The reference position of the particle with global id `id`.
  Vec3 position(int id) const;
  std::string advice() const;
  void record();
  void write_fields() { fields_.write(h_.particles.time); }
  std::string progress() const;
  /// The run's whole state into a checkpoint (the field steps so far split off into a part of
  /// it), and back on a restart.
  void save(io::Checkpoints& checkpoints, const io::Saver& save);
  void restore(const io::Loader& load);

  /// Counts, rates and status of the finished loop into the result.
  void finish(const LoopReport& loop);
  /// The least energy the energy balance's error is measured against: a body that starts at
  /// rest in a stressed state (a staged run) has only round-off energies at its first steps,
  /// whose ratio means nothing; its stored strain energy is the scale.
  void set_energy_scale(double energy) { energy_scale_ = energy; }

private:
  template <class Visit> void for_each_state(const Visit& visit);
  double max_pressure() const;
  double von_mises(int i) const;
  /// The stress tensor's components as fields of their own.
  void stress_fields();
  /// Registers a field whose owned values `owned` fills (`per` a particle, in local order);
  /// it is written in global-id order.
  void field(std::string name, int per, io::FieldOutput::Fill owned);
  sph::Hydro& h_;
  const spec::SphSpec& spec_;
  SphRunResult& r_;
  Gauges gauges_;
  io::FieldOutput fields_;
  double e0_ = 0.0, dt_ = 0.0;
  double energy_scale_ = 0.0; // the least energy the balance's error is measured against
};

} // namespace mf::explicit_dynamics
