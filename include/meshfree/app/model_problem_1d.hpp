#pragma once
// The 1D model problem of [Faraji 2007] (section 4-2) by RK Galerkin, on one rank.
#include "meshfree/app/analysis.hpp"
#include "meshfree/implicit/model_problem_1d.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/spec/problem_spec.hpp"

namespace mf::app {

/// Solves the problem and writes its results to `out`.
implicit::Model1DResult model_problem_1d(const spec::ProblemSpec& spec, io::OutputDirectory& out);

/// The table entry of `analysis: model_problem_1d`.
AnalysisEntry model_problem_1d_entry();

} // namespace mf::app
