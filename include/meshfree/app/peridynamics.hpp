#pragma once
// Explicit bond-based peridynamics run from a problem file: particles, bonds, loads and
// impactors from the spec, velocity-Verlet steps to the end time, histories and fields.
#include "meshfree/core/timer.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/pd/dynamics.hpp"
#include <string>
#include <vector>

namespace mf::app {

/// The body, its loading and impactors, built from a spec (no time stepping yet).
struct PdSetup {
  pd::Model model;
  pd::BondState state;
  pd::Loading loading;
  std::vector<pd::Impactor> impactors;
  std::vector<int> gauge_particle;
  std::vector<double> initial_velocity; // 3 per particle
  double dt = 0.0;
  std::string dt_limit; // what set the time step
};

PdSetup build_pd_setup(const io::ProblemSpec& spec, PhaseTimer& timer);

struct PdResult {
  int particles = 0;
  long bonds = 0; // counted once
  long steps = 0;
  double dt = 0.0;
  std::string dt_limit;
  double bond_updates_per_second = 0.0;
  io::History history;
  double max_damage = 0.0;
  long broken_bonds = 0;
  double energy_drift = 0.0; // |E_total(t) - E_total(0) - W_ext| / max(E), no dissipation only
  /// Largest |value| of every gauge component (u, v, a) over every step, not only the recorded
  /// ones: "<gauge>_<u|v|a><x|y|z>".
  std::vector<std::pair<std::string, double>> gauge_maxima;
  std::string status = "completed", stop_reason;
  PhaseTimer timer;
};

/// Runs the problem to its end time; fields go to `out` (null: none).
PdResult run_peridynamics(const io::ProblemSpec& spec, io::OutputDirectory* out);

/// history.csv and summary.json.
void write_pd_outputs(const io::ProblemSpec& spec, const PdResult& r, io::OutputDirectory& out);

} // namespace mf::app
