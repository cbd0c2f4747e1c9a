#pragma once
// A peridynamic body built from a problem file (analysis: peridynamics): the particle lattice,
// bonds and their laws, pre-cracks, constraints, loads (blasts per particle), initial velocities,
// impactors, and the time step with what set it.
#include "meshfree/core/timer.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/pd/dynamics.hpp"
#include <string>
#include <vector>

namespace mf::pd {

/// The body at t = 0, its loading and impactors (no time stepping yet).
struct Setup {
  Model model; // the particles carry their initial velocities
  BondState state;
  Loading loading;
  std::vector<Impactor> impactors;
  double dt = 0.0;
  std::string dt_limit; // what set the time step
};

Setup build_setup(const io::ProblemSpec& spec, PhaseTimer& timer);

/// The body, its bond laws, time step and blast pulses, on the log.
void log_setup(const io::ProblemSpec& spec, const Setup& setup);

} // namespace mf::pd
