#pragma once
// An SPH run from a problem file (analysis: sph): particles from the blocks, lighting times from
// the detonation point, CFL-limited steps to the end time, histories, gauges and fields.
#include "meshfree/core/timer.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/sph/hydro.hpp"
#include <string>
#include <vector>

namespace mf::app {

/// The particles of a spec, at rest state of the blocks, lit if the spec detonates.
sph::Hydro build_sph(const io::SphSpec& s);

struct SphResult {
  int particles = 0;
  long steps = 0;
  int neighbour_rebuilds = 0;
  double first_dt = 0.0, smallest_dt = 0.0;
  std::string dt_limit; // the particle that set the smallest step
  double particle_steps_per_second = 0.0;
  double peak_pressure = 0.0, energy_error = 0.0; // |E(t) - E(0)| / E(0), largest
  io::History history;
  std::vector<std::pair<std::string, double>> gauge_maxima;
  std::string status = "completed", stop_reason;
  PhaseTimer timer;
};

SphResult run_sph(const io::ProblemSpec& spec, io::OutputDirectory* out);

/// history.csv and summary.json.
void write_sph_outputs(const io::ProblemSpec& spec, const SphResult& r, io::OutputDirectory& out);

} // namespace mf::app
