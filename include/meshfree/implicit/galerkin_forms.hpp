#pragma once
// The linear forms of a Galerkin model that both the elastic and the elastoplastic solves use:
// the linear elastic system K d = f and what each boundary condition does to the body.
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <memory>
#include <string>
#include <vector>

namespace mf::implicit {

/// What a boundary condition does to the body after a solve.
struct BoundaryReport {
  std::string name;
  bool constraint = false;
  Vec2 force{0.0, 0.0};       // reaction (constraint) or applied load, on the body
  double violation_max = 0.0; // max |u^h - ubar| over the constraint's Gauss points
};

/// K d = f for linear elasticity: the stiffness, penalty terms, tractions and body force of this
/// rank's rows, with each condition's value (and the body force, the last entry) times its factor,
/// assembled in place into the matrix of a linear system solved as the problem says.
std::unique_ptr<solvers::BlockLinearSystem>
linear_elastic_system(const spec::ProblemSpec& spec, const GalerkinModel& m,
                      const std::vector<double>& factors, const solvers::PetscSession& session);

/// Reaction (the penalty force on the body) and largest gap of a displacement condition whose
/// prescribed value is scaled by `factor`, or the applied force of a traction condition, summed
/// over every rank.
BoundaryReport boundary_report(const ConditionPoints& c, const std::vector<double>& d,
                               double factor, const solvers::PetscSession& session);

} // namespace mf::implicit
