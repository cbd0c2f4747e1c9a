#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/app/elastic_static.hpp"
#include "meshfree/implicit/adaptive_pilots.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/galerkin_plan.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include <limits>

namespace mf::app {

implicit::ElastoplasticResult elastoplastic_static(const implicit::AdaptedProblem& problem,
                                                   const solvers::PetscSession& session,
                                                   io::OutputDirectory* out, const std::string& dir,
                                                   const io::Restart* restart) {
  const spec::ProblemSpec& spec = problem.spec;
  implicit::ElastoplasticResult r =
      implicit::solve_elastoplastic_static(spec, session, out, dir, restart);
  implicit::record_adaptation(problem, r);
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) implicit::write_elastoplastic_outputs(spec, r, session, *out);
  }
  return r;
}

namespace {

void check(const spec::ProblemSpec& spec) {
  describe_galerkin(spec);
  implicit::require_increment_output(spec, "out/" + spec.name);
}

void admit(const spec::ProblemSpec& spec, const std::string& folder) {
  admit_galerkin(spec, folder);
  implicit::require_increment_output(spec, folder);
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
  const auto r = elastoplastic_static(implicit::adapted_elastoplastic(q.spec, q.session), q.session,
                                      q.out, q.dir, q.restart);
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
