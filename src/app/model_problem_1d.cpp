#include "meshfree/app/model_problem_1d.hpp"
#include "meshfree/implicit/model_problem_1d_output.hpp"
#include <iostream>

namespace mf::app {

implicit::Model1DResult model_problem_1d(const spec::ProblemSpec& spec, io::OutputDirectory& out) {
  const implicit::Model1DResult r = implicit::solve_model_problem_1d(spec);
  implicit::write_model_1d_outputs(spec, r, out);
  return r;
}

namespace {

void describe(const spec::ProblemSpec& spec) {
  std::cout << "  1D model problem on [0, " << spec.model_1d().length << "], spacing "
            << spec.model_1d().discretisation.spacing << "\n";
}

/// On one rank: the others have nothing to do.
RunOutcome run(const RunRequest& q) {
  if (q.session.rank() == 0) model_problem_1d(q.spec, *q.out);
  return {};
}

} // namespace

AnalysisEntry model_problem_1d_entry() {
  return {spec::Analysis::ModelProblem1D, // analysis
          "model_problem_1d",             // name
          false,                          // checkpoints
          false,                          // folder at first file
          describe,                       // describe
          nullptr,                        // check
          nullptr,                        // admit
          nullptr,                        // end time
          run};                           // run
}

} // namespace mf::app
