#pragma once
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <cmath>
#include <string>
#include <vector>

const mf::solvers::PetscSession& test_session();

inline std::string source_path(const std::string& relative) {
  return std::string(MESHFREE_SOURCE_DIR) + "/" + relative;
}

inline mf::spec::ProblemSpec load_problem(const std::string& name,
                                          const std::vector<std::string>& overrides = {}) {
  return mf::spec::read_problem(source_path("problems/" + name + ".yaml"), overrides);
}

/// Least-squares slope of log(error) against log(h).
inline double convergence_rate(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
