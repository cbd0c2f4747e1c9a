#include "meshfree/app/elastic_static.hpp"
#include "meshfree/implicit/adaptive_pilots.hpp"
#include "meshfree/implicit/elastic_output.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/galerkin_plan.hpp"
#include "meshfree/implicit/solid_elastic.hpp"
#include <iostream>

namespace mf::app {

implicit::ElasticResult elastic_static(const implicit::AdaptedProblem& problem,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory* out) {
  const spec::ProblemSpec& spec = problem.spec;
  // The display mesh on every rank alike (its nodal average is collective; `out` is rank 0's).
  implicit::ElasticResult r = implicit::solve_elastic_static(spec, session, true);
  implicit::record_adaptation(problem, r);
  {
    PhaseTimer::Scope scope(r.timer, "output");
    if (out) implicit::write_elastic_outputs(spec, r, session, *out);
  }
  return r;
}

namespace {

RunOutcome run(const RunRequest& q) {
  if (!q.spec.is_solid()) {
    log_phases(
        elastic_static(implicit::adapted_elastic(q.spec, q.session), q.session, q.out).timer);
    return {};
  }
  auto r = implicit::solve_solid_elastic(q.spec, q.session); // a 3D body
  write_and_log(r, q.out, [&](io::OutputDirectory& o) {
    implicit::write_solid_elastic_outputs(q.spec, r, q.session, o);
  });
  return {};
}

} // namespace

void describe_galerkin(const spec::ProblemSpec& spec) {
  implicit::print_galerkin_plan(spec, std::cout);
}

void admit_galerkin(const spec::ProblemSpec& spec, const std::string&) {
  if (spec.is_galerkin() && spec.galerkin().discretisation.method == spec::Method::Fem)
    implicit::read_fe_mesh(spec);
}

AnalysisEntry elastic_static_entry() {
  return {spec::Analysis::ElasticStatic, // analysis
          "elastic_static",              // name
          false,                         // checkpoints
          false,                         // folder at first file
          describe_galerkin,             // describe
          nullptr,                       // check
          admit_galerkin,                // admit
          nullptr,                       // end time
          run};                          // run
}

} // namespace mf::app
