#pragma once
// What `meshfree check` says of an explicit run before it starts (its particles, bonds, time step,
// steps and memory), and the bound a staged run puts on its explicit stage before the preload:
// both build the set-up as the run builds it and refuse what the run would refuse.
#include "meshfree/spec/problem_spec.hpp"
#include <ostream>
#include <string>

namespace mf::explicit_dynamics {

/// A peridynamic run's particles, bonds, horizon, time step, steps and memory.
void print_pd_plan(const spec::ProblemSpec& spec, std::ostream& os);
/// An SPH run's particles, first CFL step, steps and memory.
void print_sph_plan(const spec::ProblemSpec& spec, std::ostream& os);

/// The run's set-up built to bound it: a run that would never end or not fit on the disk of
/// `folder` is refused. No warning: a staged run bounds its explicit stage so before the preload,
/// and the stage warns of clamped intervals as it starts.
void require_finite_pd_run(const spec::ProblemSpec& spec, const std::string& folder);
void require_finite_sph_run(const spec::ProblemSpec& spec, const std::string& folder);

} // namespace mf::explicit_dynamics
