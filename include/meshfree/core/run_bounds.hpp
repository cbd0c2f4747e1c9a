#pragma once
// The counts a run will perform (steps, increments, frames, checkpoints), bounded before anything
// runs: a count that would keep the machine busy past a week, or fill its disk, is refused with
// the key that asked for it. Every count is a floating-point estimate, so that a tiny interval or
// a huge end time cannot overflow an integer on the way (1e29 s once printed
// "-9223372036854775808 steps").
#include <string>

namespace mf {

/// Work one core does per second, as the bound on a run's wall time counts it: a peridynamic
/// particle's step with about 113 bonds takes about 0.5 us (docs/architecture.md), an SPH
/// particle's step a few times that, and a Galerkin degree of freedom's increment (a few Newton
/// iterations, each an assembly and a solve) about 50 us (10^6 DOFs solved in 45 s).
namespace work_per_second {
constexpr double pd_particle_steps = 2.0e6;
constexpr double sph_particle_steps = 5.0e5;
constexpr double galerkin_dof_increments = 2.0e4;
} // namespace work_per_second

/// The longest a run may be estimated to take on this machine's cores.
constexpr double max_run_seconds = 7.0 * 24.0 * 3600.0;

/// The cores this process may use (OpenMP's thread count, at least 1).
int cores_here();

/// Stops with "<key>: <what>: about N, about D days on the C cores here at R per second per
/// core, more than the 7 days a run may take" when count / (R C) exceeds max_run_seconds.
void require_run_time(const std::string& key, const std::string& what, double count,
                      double per_second_per_core);

/// Stops with "<key>: <what>: about N, about X GiB at B bytes each, more than the Y GiB free on
/// the disk of FOLDER" when count * bytes_each exceeds the free space of `folder` (or of its
/// nearest existing parent).
void require_disk(const std::string& key, const std::string& what, double count,
                  double bytes_each, const std::string& folder);

/// The first multiple of `interval` after t: where a schedule goes on after an instant t,
/// computed at once (adding the interval until it passes t never ends when the interval is
/// below t's rounding, 1e-20 after 1e-5).
double next_multiple_after(double t, double interval);

} // namespace mf
