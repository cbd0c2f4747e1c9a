#pragma once
// Gauss-point values carried to the nodes for output, on a plane or a solid model alike: at
// each node the average of the values at the points around it, weighted by phi_I(x_g)^2 w_g
// (positive for any shape functions, also where RK or serendipity functions are negative).
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <array>
#include <cstddef>
#include <vector>

namespace mf::implicit {

/// Fields values a node, node after node, on rank 0 (empty on the other ranks): `value(k, v)`
/// writes the values of row k of the model's domain table into v[0 .. Fields); every point is
/// counted once over the ranks (RankPoints::counted). A node no point touches gets zeros.
template <int Fields, class Model, class Value>
std::vector<double> nodal_averages(const Model& m, const solvers::PetscSession& session,
                                   Value value) {
  constexpr int kWith = Fields + 1; // the values, then the weight
  const int N = m.node_count();
  std::vector<double> sum(static_cast<std::size_t>(kWith) * N, 0.0);
  const auto& t = m.domain_table;
  for (int k = 0; k < t.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    std::array<double, Fields> v;
    value(k, v.data());
    for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) {
      const double a = t.phi[q] * t.phi[q] * w;
      double* s = sum.data() + static_cast<std::size_t>(kWith) * t.node[q];
      for (int f = 0; f < Fields; ++f) s[f] += a * v[f];
      s[Fields] += a;
    }
  }
  solvers::sum_on_root(session.comm(), sum);
  if (session.rank() != 0) return {};
  std::vector<double> out(static_cast<std::size_t>(Fields) * N);
  for (int I = 0; I < N; ++I) {
    const double* s = sum.data() + static_cast<std::size_t>(kWith) * I;
    const double w = s[Fields] > 0.0 ? 1.0 / s[Fields] : 0.0;
    for (int f = 0; f < Fields; ++f) out[static_cast<std::size_t>(Fields) * I + f] = s[f] * w;
  }
  return out;
}

} // namespace mf::implicit
