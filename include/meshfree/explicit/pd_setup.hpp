#pragma once
// A peridynamic body built from a problem file (analysis: peridynamics): the particle lattice,
// bonds and their laws, pre-cracks, constraints, loads (blasts per particle), initial velocities,
// impactors, and the time step with what set it.
#include "meshfree/core/timer.hpp"
#include "meshfree/pd/dynamics.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::explicit_dynamics {

/// The body at t = 0, its loading and impactors (no time stepping yet).
struct PdSetup {
  pd::Model model; // the particles carry their initial velocities
  pd::BondState state;
  pd::Loading loading;
  std::vector<pd::Impactor> impactors;
  std::optional<pd::ShortRangeContact> short_range; // discretisation.short_range_contact
  double dt = 0.0;
  std::string dt_limit;     // what set the time step
  std::string dt_key;       // the key that set it, when not the stability bound (time.dt, ...)
  long particles_total = 0; // over every rank
  long first_id = 0;        // of this rank's first owned particle (owned ids are contiguous)
};

/// On a run spread over MPI ranks (`ranks`), each rank sets up its block of particles and the
/// ghosts within reach of them (distribution/local_part.hpp). Collective.
PdSetup build_pd_setup(const spec::ProblemSpec& spec, PhaseTimer& timer,
                       const distribution::Ranks& ranks = {});

/// The body, its bond laws, time step and blast pulses, on the log.
void log_pd_setup(const spec::ProblemSpec& spec, const PdSetup& setup);

} // namespace mf::explicit_dynamics
