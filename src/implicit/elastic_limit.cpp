#include "meshfree/implicit/elastic_limit.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/materials/elastic.hpp"
#include "meshfree/solvers/parallel.hpp"

namespace mf::implicit {

namespace {

/// The largest of the candidates over every rank: `score` is the von Mises stress scaled to
/// the reference yield stress (score = vm sigma_ref / sigma_y of the point's material), `vm`
/// the von Mises stress itself.
PeakStress peak(double score, double vm, const Vec2& at, double sigma_ref,
                const solvers::PetscSession& session) {
  double x[3] = {at.x(), at.y(), vm};
  const solvers::RankMax top = solvers::max_with_location(session.comm(), score, x, 3);
  PeakStress p;
  p.von_mises = x[2];
  p.at = Vec2(x[0], x[1]);
  if (top.value > 0.0) p.fraction = sigma_ref / top.value;
  return p;
}

} // namespace

std::string elastic_limit_skipped(const spec::ProblemSpec& spec) {
  auto& galerkin = spec.galerkin();
  bool plastic = spec.plasticity().has_value();
  for (const spec::MaterialRegion& r : galerkin.material_regions)
    plastic = plastic || spec.materials[r.material].plasticity.has_value();
  if (!plastic) return "no material of the body has plasticity";
  if (galerkin.initial_stress)
    return "the body starts from an initial stress, so the stresses do not scale with the load";
  return "";
}

ElasticLimit elastic_limit(const spec::ProblemSpec& spec, const GalerkinModel& m,
                           const solvers::PetscSession& session) {
  ElasticLimit lim;
  lim.skipped = elastic_limit_skipped(spec);
  if (!lim.skipped.empty()) return lim;
  const std::vector<double>& target = spec.galerkin().steps.front().target;
  const auto system = linear_elastic_system(spec, m, target, session);
  system->solve();
  const std::vector<double> d = system->solution_everywhere();
  // First yield where sigma_vm / sigma_y of the point's material peaks, over the points of
  // plastic materials; sigma_ref is the yield stress of the analysis' material (or of the first
  // plastic one), so that one material gives the von Mises peak itself.
  double sigma_ref = spec.plasticity() ? materials::reference_strength(*spec.plasticity()) : 0.0;
  for (const spec::MaterialRegion& r : spec.galerkin().material_regions)
    if (!(sigma_ref > 0.0) && spec.materials[r.material].plasticity)
      sigma_ref = materials::reference_strength(*spec.materials[r.material].plasticity);
  const auto best_of = [&](const ShapeTable& t, const std::vector<Vec2>& x, const char* counted,
                           double& score, double& vm_best, Vec2& where) {
    const PointLaws laws = point_laws(spec, x);
    score = -1.0;
    for (int k = 0; k < t.rows(); ++k) {
      const int mat = laws.material[k];
      if (!laws.plastic[mat] || (counted && !counted[k])) continue;
      const auto [s, szz] = laws.elastic_stress(spec.model, k, strain_at(t, k, d));
      const double vm = materials::von_mises(s, szz);
      materials::Vec6 s3;
      s3 << s(0), s(1), szz, 0.0, 0.0, s(2);
      const double sc = materials::first_yield_measure(laws.params[mat], s3, sigma_ref);
      if (sc > score) score = sc, vm_best = vm, where = x[k];
    }
  };
  double score = -1.0, vm = 0.0;
  Vec2 where(0.0, 0.0);
  best_of(m.domain_table, domain_rows(m), m.domain_mine.counted.data(), score, vm, where);
  lim.gauss_points = peak(score, vm, where, sigma_ref, session);
  score = -1.0;
  if (session.rank() == 0) {
    const ShapeTable t = shapes_at(m, m.node_positions(), true);
    best_of(t, m.node_positions(), nullptr, score, vm, where);
  }
  lim.nodes = peak(score, vm, where, sigma_ref, session);
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
