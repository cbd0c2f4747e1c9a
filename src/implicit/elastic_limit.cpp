#include "meshfree/implicit/elastic_limit.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/solvers/parallel.hpp"

namespace mf::implicit {

namespace {

/// The largest of the candidates (value, position) over every rank.
PeakStress peak(double value, const Vec2& at, double sigma_y,
                const solvers::PetscSession& session) {
  double x[2] = {at.x(), at.y()};
  const solvers::RankMax top = solvers::max_with_location(session.comm(), value, x, 2);
  PeakStress p;
  p.von_mises = top.value;
  p.at = Vec2(x[0], x[1]);
  if (top.value > 0.0) p.fraction = sigma_y / top.value;
  return p;
}

} // namespace

ElasticLimit elastic_limit(const io::ProblemSpec& spec, const GalerkinModel& m,
                           const solvers::PetscSession& session) {
  ElasticLimit lim;
  const std::vector<double>& target = spec.steps.front().target;
  const BlockRows rows = assemble_linear_elastic(spec, m, target);
  const RowPattern& p = rows.pattern();
  solvers::BlockLinearSystem system(session.comm(), m.node_count(), m.own, p.offset, p.column,
                                    rows.values(), rows.rhs(), /*spd=*/true);
  system.solve();
  const std::vector<double> d = system.solution_everywhere();
  const Mat3 C = materials::elastic_matrix(spec.material, spec.model);
  const auto vm_at = [&](const ShapeTable& t, int k) {
    const Vec3 s = C * strain_at(t, k, d);
    return materials::von_mises(s, materials::out_of_plane_stress(spec.material, spec.model, s));
  };
  const double sigma_y = spec.plasticity->sigma0;
  double best = -1.0;
  Vec2 where(0.0, 0.0);
  for (int k = 0; k < m.domain_table.rows(); ++k) {
    const double vm = vm_at(m.domain_table, k);
    if (m.domain_mine.counted[k] && vm > best) best = vm, where = m.domain.x[m.domain_mine.rows[k]];
  }
  lim.gauss_points = peak(best, where, sigma_y, session);
  best = -1.0;
  if (session.rank() == 0) {
    const ShapeTable t = shapes_at(m, m.node_positions(), true);
    for (int k = 0; k < t.rows(); ++k) {
      const double vm = vm_at(t, k);
      if (vm > best) best = vm, where = m.node_positions()[k];
    }
  }
  lim.nodes = peak(best, where, sigma_y, session);
  lim.fraction = lim.nodes.fraction;
  for (double f : target) lim.factors.push_back(lim.fraction * f);
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    BoundaryReport r = boundary_report(m.conditions[b], d, target[b], session);
    r.force *= lim.fraction; // linear elasticity: forces scale with the load
    lim.boundary.push_back(r);
  }
  return lim;
}

} // namespace mf::implicit
