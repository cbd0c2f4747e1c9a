#pragma once
// First yield under the first load step of an elastoplastic analysis, from one linear elastic
// solve on the same Galerkin model.
#include "meshfree/implicit/galerkin_forms.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <limits>
#include <string>
#include <vector>

namespace mf::implicit {

/// The largest von Mises stress of the elastic solution at the end of the first step, over one
/// kind of point.
struct PeakStress {
  double von_mises = 0.0;
  Vec2 at{0.0, 0.0};
  double fraction = std::numeric_limits<double>::infinity(); // sigma_y0 / von_mises
};

/// First yield under the first step's loading, from a linear elastic solve (loads are
/// proportional within a step, so the elastic stresses scale with the load factor). First yield
/// is where the stress at a node reaches sigma_y0: nodes lie inside the body and on its
/// boundary, where stress concentrations peak. The peak over the Gauss points, which lie inside
/// and near the boundary are the least accurate points of a meshfree stress field, is reported
/// beside it.
struct ElasticLimit {
  PeakStress gauss_points, nodes;
  double fraction = std::numeric_limits<double>::quiet_NaN(); // of the first step's targets
  std::vector<double> factors;                                // at first yield
  std::vector<BoundaryReport> boundary;                       // reactions and loads there
  std::string skipped; // why first yield was not searched (empty when it was)
};

/// Why first yield is not searched (no plastic material, or an initial stress), or "".
std::string elastic_limit_skipped(const spec::ProblemSpec& spec);

/// Solves the first step's elastic problem on every rank and finds first yield; over the points
/// of plastic materials, each against its own yield stress.
ElasticLimit elastic_limit(const spec::ProblemSpec& spec, const GalerkinModel& m,
                           const solvers::PetscSession& session);

} // namespace mf::implicit
