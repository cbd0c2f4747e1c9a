#pragma once
// What a Galerkin model of a plane or a solid body needs to know of its integration points
// before any shape function: the nodes covering each point, the points this rank integrates and
// the exact pattern of its block rows; and how messages name a point. One code for both
// dimensions: a model is GalerkinModel or SolidModel, a point an Eigen vector of 2 or 3.
#include "meshfree/core/error.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include <string>
#include <vector>

namespace mf::implicit {

/// "x, y" or "x, y, z": a point's coordinates as messages give them.
template <class Point> std::string point_text(const Point& x) {
  std::string text = detail::concat(x(0));
  for (int c = 1; c < x.size(); ++c) text += detail::concat(", ", x(c));
  return text;
}

/// Refuses a point that no node covers.
template <class Point> void require_covered(const Csr& support, const std::vector<Point>& x) {
  for (int r = 0; r < support.rows(); ++r)
    MF_REQUIRE(support.size(r) > 0, "integration point (", point_text(x[r]),
               ") is covered by no node: raise discretisation.dilation");
}

/// The support lists of the model's domain and condition points, the points this rank
/// integrates and the pattern of its block rows (the constraining conditions couple their nodes
/// too); `widen` may widen the domain points' supports (it takes and gives a Csr).
template <class Model, class Widen>
void couple_points(Model& m, const solvers::PetscSession& session, Widen&& widen) {
  const int N = m.node_count();
  m.domain_support = m.space->support_lists(m.domain.x);
  require_covered(m.domain_support, m.domain.x);
  m.domain_support = widen(std::move(m.domain_support));
  m.domain_mine = rank_points(m.domain_support, m.own, N, session);
  std::vector<const Csr*> coupling{&m.domain_support};
  for (auto& c : m.conditions) {
    c.support = m.space->support_lists(c.points.x);
    require_covered(c.support, c.points.x);
    if (c.bc->constrains) coupling.push_back(&c.support);
    c.mine = rank_points(c.support, m.own, N, session);
  }
  m.pattern = coupling_pattern(coupling, N, m.own.begin, m.own.end);
}

template <class Model> void couple_points(Model& m, const solvers::PetscSession& session) {
  couple_points(m, session, [](Csr s) { return s; });
}

} // namespace mf::implicit
