#pragma once
// The load schedule of a quasi-static analysis: each step moves the load factors linearly from
// where the last step left them to its targets in increments, each solved by Newton; an
// increment that does not converge is halved and retried, and a cut increment grows back after
// easy ones.
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include <functional>
#include <string>
#include <vector>

namespace mf::implicit {

/// How the schedule ended.
struct ScheduleOutcome {
  std::string status = "completed"; // or "stopped": an increment failed after every cut-back
  std::string stop_reason;
  double newton_seconds = 0.0; // in Newton solves
};

/// Called with each converged increment (the system committed, `d` converged) and whether the
/// fields are due; returns the increment as recorded.
using IncrementDone = std::function<const IncrementRecord&(IncrementRecord rec, bool write_fields)>;

/// Runs spec.steps from the unloaded state in `d`; `d` ends at the last converged state.
ScheduleOutcome run_load_schedule(const io::ProblemSpec& spec, ElastoplasticSystem& problem,
                                  solvers::NonlinearBlockSystem& newton, std::vector<double>& d,
                                  const IncrementDone& done);

/// "pull 0.002, tension 308": the factors of the conditions that drive the body.
std::string factors_text(const io::ProblemSpec& spec, const std::vector<double>& f);

} // namespace mf::implicit
