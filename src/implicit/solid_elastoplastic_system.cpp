#include "meshfree/implicit/solid_elastoplastic_system.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/point_updates.hpp"
#include "meshfree/implicit/residual_terms.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace mf::implicit {

namespace {

/// Adds node-block vectors (3 values a node) into the owned rows of a plain array.
struct OwnedRows3 {
  int begin, end;
  double* r;
  void add(const int* nodes, int n, const double* v) const {
    for (int a = 0; a < n; ++a) {
      const int I = nodes[a];
      if (I < begin || I >= end) continue;
      for (int c = 0; c < 3; ++c) r[3 * (I - begin) + c] += v[3 * a + c];
    }
  }
};

} // namespace

materials::ConstitutiveModel solid_material_law(const spec::ProblemSpec& spec) {
  materials::ConstitutiveModel p = material_parameters(spec, spec.solid().material_index);
  if (!spec.materials[spec.solid().material_index].plasticity)
    std::get<materials::J2Parameters>(p).sigma0 = std::numeric_limits<double>::infinity();
  return p;
}

SolidElastoplasticSystem::SolidElastoplasticSystem(const spec::ProblemSpec& spec,
                                                   const SolidModel& m)
    : spec_(spec), m_(m), params_(solid_material_law(spec)), states_(m.domain_table.rows()),
      penalty_(m.pattern, 3), scatter_(m.domain_table.offset, m.domain_table.node, m.pattern) {
  const int rows = m.pattern.rows();
  const spec::SolidSpec& s = spec.solid();
  loads_.assign(s.boundary.size() + 1,
                std::vector<double>(3 * static_cast<std::size_t>(rows), 0.0));
  counts_in_scale_.assign(loads_.size(), 0);
  std::vector<double> K, f;
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    const SolidConditionPoints& c = m.conditions[b];
    const OwnedRows3 into{m.pattern.begin, m.pattern.end, loads_[b].data()};
    counts_in_scale_[b] = !c.bc->constrains;
    for (int k = 0; k < c.table.rows(); ++k) {
      const int n = c.table.offset[k + 1] - c.table.offset[k];
      const int* nodes = c.table.node.data() + c.table.offset[k];
      const double w = c.points.weight[c.mine.rows[k]];
      f.resize(3 * n);
      if (c.bc->constrains) {
        K.resize(9 * static_cast<std::size_t>(n) * n);
        solid_point_penalty(c.table, k, c.bc->penalty * w, c.bc->mask, c.values[k], K.data(),
                            f.data());
        penalty_.add_matrix(nodes, n, K.data());
      } else {
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i)
            f[3 * a + i] = w * c.table.phi[c.table.offset[k] + a] * c.values[k](i);
      }
      into.add(nodes, n, f.data());
    }
  }
  const Vec3 body = s.body_force;
  if (!body.isZero()) {
    const SolidShapeTable& t = m.domain_table;
    const OwnedRows3 into{m.pattern.begin, m.pattern.end, loads_.back().data()};
    for (int k = 0; k < t.rows(); ++k) {
      const int n = t.offset[k + 1] - t.offset[k];
      f.resize(3 * n);
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < 3; ++i)
          f[3 * a + i] = m.domain_weight[k] * t.phi[t.offset[k] + a] * body(i);
      into.add(t.node.data() + t.offset[k], n, f.data());
    }
    counts_in_scale_.back() = 1;
  }
  factors_.assign(loads_.size(), 0.0);
}

void SolidElastoplasticSystem::commit() {
  states_.commit();
  committed_d_ = states_valid_ ? states_d_ : std::vector<double>{};
}

void SolidElastoplasticSystem::residual(const std::vector<double>& d, double* r,
                                        solvers::ResidualSums& sums) {
  update_materials(d);
  const int rows = m_.pattern.rows();
  std::fill(r, r + 3 * rows, 0.0);
  const SolidShapeTable& t = m_.domain_table;
  const OwnedRows3 into{m_.pattern.begin, m_.pattern.end, r};
  std::vector<std::vector<double>> f(PointGroups::threads());
  m_.domain_groups.for_each([&](int k, int thread) {
    const int n = t.offset[k + 1] - t.offset[k];
    f[thread].resize(3 * n);
    solid_point_force(t, k, m_.domain_weight[k] * states_.stress[k], f[thread].data());
    into.add(t.node.data() + t.offset[k], n, f[thread].data());
  });
  // K_pen d apart from f_int: its magnitude sets the round-off floor of the penalty rows.
  std::vector<double> penalty(3 * static_cast<std::size_t>(rows), 0.0);
  penalty_.multiply_add(d, penalty.data());
  finish_residual(r, penalty, loads_, factors_, counts_in_scale_, sums);
}

void SolidElastoplasticSystem::jacobian(const std::vector<double>& d,
                                        solvers::BlockValueArrays values) {
  update_materials(d);
  BlockRows tangent(m_.pattern, values, 3);
  tangent.copy_values(penalty_);
  const SolidShapeTable& t = m_.domain_table;
  const int threads = PointGroups::threads();
  std::vector<std::vector<double>> K(threads), work(threads);
  std::vector<std::vector<int>> slots(threads);
  m_.domain_groups.for_each([&](int k, int thread) {
    const int n = t.offset[k + 1] - t.offset[k];
    K[thread].resize(9 * static_cast<std::size_t>(n) * n);
    solid_point_stiffness(t, k, m_.domain_weight[k] * states_.tangent[k], K[thread].data(),
                          work[thread]);
    tangent.add_matrix_at(t.node.data() + t.offset[k], scatter_.slots(k, slots[thread]), n,
                          K[thread].data());
  });
}

std::vector<int> SolidElastoplasticSystem::needed_nodes() const {
  return nodes_read(m_.domain_table.node, m_.pattern, m_.conditions);
}

void SolidElastoplasticSystem::update_materials(const std::vector<double>& d) {
  if (states_valid_ && d == states_d_) return;
  if (d == committed_d_) { // the response of the converged increment (see commit)
    states_.take_back();
    states_d_ = d;
    states_valid_ = true;
    return;
  }
  const SolidShapeTable& t = m_.domain_table;
  states_valid_ = false;
  const auto update = [&](int k) {
    const Vec6 eps = solid_strain_at(t, k, d);
    MF_REQUIRE(eps.allFinite(), "the strain is not finite");
    const materials::StressUpdate3D r =
        materials::stress_update_3d(params_, eps, states_.committed[k]);
    MF_REQUIRE(r.stress.allFinite(), "the stress is not finite");
    states_.trial[k] = r.state;
    states_.stress[k] = r.stress;
    states_.tangent[k] = r.tangent;
    states_.plastic[k] = r.plastic;
  };
  update_every_point(t.rows(), update, [&](int k) { return m_.domain.x[m_.domain_mine.rows[k]]; });
  states_d_ = d;
  states_valid_ = true;
}

} // namespace mf::implicit
