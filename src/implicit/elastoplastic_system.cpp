#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/core/progress.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_updates.hpp"
#include "meshfree/implicit/residual_terms.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace mf::implicit {

namespace {

using Clock = std::chrono::steady_clock;

/// Adds node-block vectors into the owned rows of a plain array.
struct OwnedRowAdder {
  int begin, end;
  double* r;
  void operator()(const int* nodes, int n, const double* v) const {
    for (int a = 0; a < n; ++a) {
      const int I = nodes[a];
      if (I < begin || I >= end) continue;
      r[2 * (I - begin)] += v[2 * a];
      r[2 * (I - begin) + 1] += v[2 * a + 1];
    }
  }
};

} // namespace

ElastoplasticSystem::ElastoplasticSystem(const spec::ProblemSpec& spec, const GalerkinModel& m)
    : spec_(spec), m_(m), laws_(point_laws(spec, domain_rows(m))), states_(m.domain_table.rows()),
      penalty_(m.pattern), scatter_(m.domain_table, m.pattern) {
  MF_REQUIRE(m.domain_groups.rows() == m.domain_table.rows(),
             "ElastoplasticSystem: the model's points are not grouped for assembly");
  if (!scatter_.kept())
    log::info("the tangent's slot map would take ", describe_bytes(scatter_.full_bytes()),
              ", more than a quarter of the memory here: each point's slots are searched anew "
              "at every assembly instead");
  const int rows = m.pattern.rows();
  loads_.assign(spec.galerkin().boundary.size() + 1, std::vector<double>(2 * rows, 0.0));
  counts_in_scale_.assign(loads_.size(), 0);
  const auto add_penalty_matrix = [&](const int* nodes, int n, const double* v) {
    penalty_.add_matrix(nodes, n, v);
  };
  for (std::size_t b = 0; b < m.conditions.size(); ++b) {
    const ConditionPoints& c = m.conditions[b];
    const OwnedRowAdder into{m.pattern.begin, m.pattern.end, loads_[b].data()};
    if (c.bc->constrains) {
      add_penalty(c.table, c.weight, c.bc->mask, c.bc->penalty, c.values, add_penalty_matrix, into);
    } else {
      add_load(c.table, c.weight, c.values, into);
      counts_in_scale_[b] = 1;
    }
  }
  if (has_body_force(spec)) {
    const OwnedRowAdder into{m.pattern.begin, m.pattern.end, loads_.back().data()};
    add_load(m.domain_table, m.domain_weight, laws_.body_force, into);
    counts_in_scale_.back() = 1;
  }
  factors_.assign(loads_.size(), 0.0);
}

void ElastoplasticSystem::commit() {
  states_.commit();
  committed_d_ = states_valid_ ? states_d_ : std::vector<double>{};
}

void ElastoplasticSystem::start_from(std::vector<materials::MaterialState> history) {
  MF_REQUIRE(history.size() == states_.committed.size(),
             "ElastoplasticSystem: a carried history must have one state a point");
  states_.committed = std::move(history);
  states_.trial = states_.committed;
  states_valid_ = false;
  committed_d_.clear();
}

void ElastoplasticSystem::residual(const std::vector<double>& d, double* r,
                                   solvers::ResidualSums& sums) {
  const auto t0 = Clock::now();
  update_materials(d);
  const int rows = m_.pattern.rows();
  std::fill(r, r + 2 * rows, 0.0);
  add_internal_force(m_.domain_table, m_.domain_groups, m_.domain_weight, states_.stress,
                     OwnedRowAdder{m_.pattern.begin, m_.pattern.end, r});
  // K_pen d apart from f_int: its magnitude sets the round-off floor of the penalty rows.
  std::vector<double>& penalty = penalty_force_;
  penalty.assign(2 * static_cast<std::size_t>(rows), 0.0);
  penalty_.multiply_add(d, penalty.data());
  finish_residual(r, penalty, loads_, factors_, counts_in_scale_, sums);
  if (share_ != 0.0)
    for (std::size_t i = 0; i < imbalance_.size(); ++i) r[i] -= share_ * imbalance_[i];
  residual_seconds_ += seconds_since(t0);
}

void ElastoplasticSystem::jacobian(const std::vector<double>& d, solvers::BlockValueArrays values) {
  const auto t0 = Clock::now();
  update_materials(d);
  BlockRows tangent(m_.pattern, values);
  tangent.copy_values(penalty_);
  const ShapeTable& t = m_.domain_table;
  const int threads = PointGroups::threads();
  std::vector<std::vector<double>> block(threads);
  std::vector<std::vector<int>> slots(threads);
  // A tangent is assembled at every Newton iteration: large systems report it only when it
  // takes longer than 10 s (no tenths, no 100% line, which would double the solve's lines).
  const bool report = 2.0 * m_.node_count() >= log::kProgressUnknowns;
  log::PhaseProgress progress("tangent assembly", t.rows(), report, {}, {}, false);
  m_.domain_groups.for_each([&](int k, int thread) {
    const int n = t.offset[k + 1] - t.offset[k];
    block[thread].resize(4 * n * n);
    point_stiffness(t, k, m_.domain_weight[k] * states_.tangent[k], block[thread].data());
    tangent.add_matrix_at(t.node.data() + t.offset[k], scatter_.slots(k, slots[thread]), n,
                          block[thread].data());
    progress.count_one(thread);
  });
  jacobian_seconds_ += seconds_since(t0);
}

double ElastoplasticSystem::initial_stress_imbalance_squared() const {
  const int rows = m_.pattern.rows();
  std::vector<double> f(2 * static_cast<std::size_t>(rows), 0.0);
  std::vector<Vec3> change(states_.stress.size());
  for (std::size_t k = 0; k < change.size(); ++k)
    change[k] = laws_.initial_stress.empty()
                    ? states_.stress[k]
                    : Vec3(states_.stress[k] - laws_.initial_stress[k].head<3>());
  add_internal_force(m_.domain_table, m_.domain_groups, m_.domain_weight, change,
                     OwnedRowAdder{m_.pattern.begin, m_.pattern.end, f.data()});
  double sum = 0.0;
  for (double v : f) sum += v * v;
  return sum;
}

std::vector<int> ElastoplasticSystem::needed_nodes() const {
  return nodes_read(m_.domain_table.node, m_.pattern, m_.conditions);
}

void ElastoplasticSystem::update_materials(const std::vector<double>& d) {
  if (states_valid_ && d == states_d_) return;
  if (d == committed_d_) {
    states_.take_back();
    states_d_ = d;
    states_valid_ = true;
    return;
  }
  const ShapeTable& t = m_.domain_table;
  const materials::PlaneModel model = spec_.model;
  states_valid_ = false;
  const auto update = [&](int k) {
    const Vec3 eps = strain_at(t, k, d);
    MF_REQUIRE(eps.allFinite(), "the strain is not finite");
    const materials::StressUpdate2D r = laws_.update(model, k, eps, states_.committed[k]);
    MF_REQUIRE(r.stress.allFinite(), "the stress is not finite");
    states_.trial[k] = r.state;
    states_.stress[k] = r.stress;
    states_.stress_zz[k] = r.stress_zz;
    states_.tangent[k] = r.tangent;
    states_.plastic[k] = r.plastic;
  };
  update_every_point(t.rows(), update, [&](int k) { return m_.domain.x[m_.domain_mine.rows[k]]; });
  states_d_ = d;
  states_valid_ = true;
}

} // namespace mf::implicit
