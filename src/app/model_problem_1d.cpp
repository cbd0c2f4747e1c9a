#include "meshfree/app/model_problem_1d.hpp"
#include "meshfree/implicit/model_problem_1d_output.hpp"

namespace mf::app {

implicit::Model1DResult model_problem_1d(const io::ProblemSpec& spec, io::OutputDirectory& out) {
  const implicit::Model1DResult r = implicit::solve_model_problem_1d(spec);
  implicit::write_model_1d_outputs(spec, r, out);
  return r;
}

} // namespace mf::app
