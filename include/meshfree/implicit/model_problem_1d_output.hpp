#pragma once
// The files of the 1D model problem: line_solution.csv, fields, history.csv and summary.json.
#include "meshfree/implicit/model_problem_1d.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::implicit {

void write_model_1d_outputs(const spec::ProblemSpec& spec, const Model1DResult& r,
                            io::OutputDirectory& out);

} // namespace mf::implicit
