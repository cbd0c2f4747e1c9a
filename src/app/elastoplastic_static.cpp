#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/app/elastic_static.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/galerkin_plan.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include <limits>

namespace mf::app {

implicit::ElastoplasticResult elastoplastic_static(const spec::ProblemSpec& spec,
                                                   const solvers::PetscSession& session,
                                                   io::OutputDirectory* out, const std::string& dir,
                                                   const io::Restart* restart,
                                                   std::optional<implicit::Adaptation> adaptation) {
  implicit::ElastoplasticResult r =
      implicit::solve_elastoplastic_static(spec, session, out, dir, restart);
  r.adaptation = std::move(adaptation);
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) implicit::write_elastoplastic_outputs(spec, r, session, *out);
  }
  return r;
}

/// Each increment is a Newton solve over every degree of freedom that writes a field frame, a
/// Gauss-point frame and a display-mesh frame, about 700 bytes per node together (measured on
/// plate_plastic_thesis, README.md "Running").
void require_increment_output(const spec::ProblemSpec& spec, const std::string& folder) {
  const auto& steps = spec.is_solid() ? spec.solid().steps : spec.galerkin().steps;
  const double nodes = implicit::estimated_nodes(spec);
  const std::size_t listed = spec.is_galerkin() && spec.galerkin().initial_stress; // "geostatic"
  double frames = 1.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    frames += steps[k].increments;
    if (k < listed) continue;
    const std::string key = "steps[" + std::to_string(k - listed) + "].increments";
    require_run_time(key, "DOF-increments of the schedule so far", frames * 2.0 * nodes,
                     work_per_second::galerkin_dof_increments);
    require_disk(key, "field frames of the schedule so far", frames, 700.0 * nodes, folder);
  }
}

namespace {

void check(const spec::ProblemSpec& spec) {
  describe_galerkin(spec);
  require_increment_output(spec, "out/" + spec.name);
}

void admit(const spec::ProblemSpec& spec, const std::string& folder) {
  admit_galerkin(spec, folder);
  require_increment_output(spec, folder);
}

/// Checkpoints count increments: no bound in time.
double end_time(const spec::ProblemSpec&) {
  return std::numeric_limits<double>::infinity();
}

RunOutcome run(const RunRequest& q) {
  if (q.spec.is_solid()) { // a 3D body
    auto r = implicit::solve_solid_elastoplastic(q.spec, q.session, q.out);
    write_and_log(r, q.out, [&](io::OutputDirectory& o) {
      implicit::write_solid_elastoplastic_outputs(q.spec, r, q.session, o);
    });
    return {r.status == "completed" ? 0 : 3, r.status};
  }
  // Pilot solves of the schedule in fewer increments, without output, where the cloud adapts.
  const implicit::AdaptedProblem p =
      implicit::adapted_problem(q.spec, [&](const spec::ProblemSpec& s) {
        return implicit::solve_elastoplastic_static(implicit::pilot_spec(s), q.session, nullptr)
            .estimate;
      });
  const auto r = elastoplastic_static(p.spec, q.session, q.out, q.dir, q.restart, p.adaptation);
  log_phases(r.timer);
  return {r.status == "completed" ? 0 : 3, r.status};
}

} // namespace

AnalysisEntry elastoplastic_static_entry() {
  return {spec::Analysis::ElastoplasticStatic, // analysis
          "elastoplastic_static",              // name
          true,                                // checkpoints
          false,                               // folder at first file
          describe_galerkin,                   // describe
          check,                               // check
          admit,                               // admit
          end_time,                            // end time
          run};                                // run
}

} // namespace mf::app
