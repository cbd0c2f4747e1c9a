#pragma once
// The 1D model problem of [Faraji 2007] (section 4-2): y'' + f = 0 on [0, L], y(0) = y(L) = 0,
// solved by RK Galerkin from the potential Pi = 1/2 int y'^2 dx - int f y dx ([Faraji 2007]
// eq. 4-2), with background Gauss cells and penalty end conditions.
#include "meshfree/core/timer.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <vector>

namespace mf::implicit {

struct Model1DResult {
  int nodes = 0, points = 0;
  std::vector<double> x, y, y_exact, dy, dy_exact; // on a fine sampling of [0, L]
  double error_l2 = 0.0, error_h1 = 0.0;           // relative, from the Gauss points
  double error_max = 0.0;                          // max |y^h - y| / max |y| on the sampling
  PhaseTimer timer;
};

double model_1d_exact(const spec::ModelProblem1D& p, double x);
double model_1d_exact_slope(const spec::ModelProblem1D& p, double x);
double model_1d_source(const spec::ModelProblem1D& p, double x);

Model1DResult solve_model_problem_1d(const spec::ProblemSpec& spec);

} // namespace mf::implicit
