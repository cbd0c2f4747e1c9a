#pragma once
// An SPH run as the explicit time loop drives it (explicit/time_loop.hpp): CFL-limited midpoint
// steps of a built body, a history row per recorded instant (sph::energies and their balance, peak
// pressure, gauges), gauge maxima over every step, and fields of the body's particles.
#include "meshfree/core/timer.hpp"
#include "meshfree/explicit/gauges.hpp"
#include "meshfree/explicit/time_loop.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/io/sph_spec.hpp"
#include "meshfree/sph/hydro.hpp"
#include "meshfree/sph/step.hpp"
#include <string>
#include <utility>
#include <vector>

namespace mf::explicit_dynamics {

struct SphRunResult {
  int particles = 0;
  long steps = 0;
  int neighbour_rebuilds = 0;
  double neighbour_seconds = 0.0; // of the stepping time, in neighbour checks and builds
  long neighbour_pairs = 0;       // directed pairs in the last neighbour list
  long neighbour_list_bytes = 0;  // its size: partners and row offsets
  double first_dt = 0.0, smallest_dt = 0.0;
  std::string dt_limit; // the particle that set the smallest step
  double particle_steps_per_second = 0.0;
  double peak_pressure = 0.0, energy_error = 0.0; // |E(t) - E(0) - W| / scale, largest
  io::History history;
  /// Largest |pressure| and speed of every gauge over every step: "<gauge>_<pressure|speed>".
  std::vector<std::pair<std::string, double>> gauge_maxima;
  std::string status = "completed", stop_reason;
  PhaseTimer timer;
};

class SphRun {
public:
  /// The history's columns and the gauges of the body `h` at t = 0; fields go to `out` (null:
  /// none).
  SphRun(sph::Hydro& h, const io::SphSpec& spec, io::OutputDirectory* out, SphRunResult& result);

  double time() const { return h_.particles.time; }
  long step() const { return h_.particles.step; }
  bool time_step(double remaining, double& dt, std::string& why);
  void advance(double dt, bool) { sph::advance(h_, dt); }
  void track();
  int nonfinite() const;
  Vec3 position(int i) const { return h_.particles.reference(i); }
  std::string advice() const;
  void record();
  void write_fields() { fields_.write(h_.particles.time); }
  std::string progress() const;

  /// Counts, rates and status of the finished loop into the result.
  void finish(const LoopReport& loop);

private:
  double max_pressure() const;
  double von_mises(int i) const;
  sph::Hydro& h_;
  const io::SphSpec& spec_;
  SphRunResult& r_;
  int n_; // the owned particles (ghosts, mirror images, follow them)
  Gauges gauges_;
  io::FieldOutput fields_;
  double e0_ = 0.0, dt_ = 0.0;
};

} // namespace mf::explicit_dynamics
