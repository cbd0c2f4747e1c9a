#include "meshfree/implicit/error_indicator.hpp"
#include "meshfree/implicit/nodal_average.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <cmath>

namespace mf::implicit {

// [Zienkiewicz & Zhu 1987] eq. 28: the error relative to the energy of the solution and the error.
double ErrorEstimate::relative() const {
  const double whole = energy2 + eta2;
  return whole > 0.0 ? std::sqrt(eta2 / whole) : 0.0;
}

namespace {

/// The nodal averages of `stress` on every rank, three values a node.
std::vector<double> averaged_stress(const GalerkinModel& m, const std::vector<Vec3>& stress,
                                    const solvers::PetscSession& session) {
  const NodalAverage a = nodal_average(m, stress, std::vector<double>(stress.size(), 0.0), session);
  std::vector<double> s(3 * static_cast<std::size_t>(m.node_count()), 0.0);
  for (std::size_t I = 0; I < a.stress.size(); ++I)
    for (int c = 0; c < 3; ++c) s[3 * I + c] = a.stress[I](c);
  solvers::broadcast(session.comm(), s, 0);
  return s;
}

} // namespace

ErrorEstimate recovery_error(const GalerkinModel& m, const std::vector<Vec3>& stress,
                             const Mat3& compliance, const solvers::PetscSession& session) {
  const std::vector<double> nodal = averaged_stress(m, stress, session);
  const ShapeTable& t = m.domain_table;
  ErrorEstimate e;
  e.node_eta2.assign(m.node_count(), 0.0);
  for (int k = 0; k < t.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    Vec3 recovered = Vec3::Zero();
    int nearest = t.node[t.offset[k]];
    double largest = -1.0;
    for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) {
      recovered += t.phi[q] * Vec3(nodal.data() + 3 * static_cast<std::size_t>(t.node[q]));
      if (t.phi[q] > largest) largest = t.phi[q], nearest = t.node[q];
    }
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    // [Zienkiewicz & Zhu 1987] eq. 11: |e|^2 = int (sigma* - sigma_h) . C^-1 (sigma* - sigma_h)
    const Vec3 gap = recovered - stress[k];
    e.node_eta2[nearest] += w * gap.dot(compliance * gap);
    e.energy2 += w * stress[k].dot(compliance * stress[k]);
  }
  solvers::sum_everywhere(session.comm(), e.node_eta2.data(), m.node_count());
  e.energy2 = solvers::sum_everywhere(session.comm(), e.energy2);
  for (double v : e.node_eta2) e.eta2 += v;
  return e;
}

} // namespace mf::implicit
