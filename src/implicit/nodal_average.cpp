#include "meshfree/implicit/nodal_average.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>

namespace mf::implicit {

namespace {

/// `value(k, v)` writes row k's sxx, syy, sxy, szz, alpha and plastic flag into v.
template <class Value>
NodalAverage average(const GalerkinModel& m, const solvers::PetscSession& session, Value value) {
  const int N = m.node_count();
  constexpr int kFields = 7; // sxx, syy, sxy, szz, alpha, plastic flag, weight
  std::vector<double> sum(static_cast<std::size_t>(kFields) * N, 0.0);
  const ShapeTable& t = m.domain_table;
  for (int k = 0; k < t.rows(); ++k) {
    if (!m.domain_mine.counted[k]) continue;
    const double w = m.domain.weight[m.domain_mine.rows[k]];
    double v[kFields - 1];
    value(k, v);
    for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) {
      const double a = t.phi[q] * t.phi[q] * w;
      double* s = sum.data() + static_cast<std::size_t>(kFields) * t.node[q];
      for (int f = 0; f < kFields - 1; ++f) s[f] += a * v[f];
      s[kFields - 1] += a;
    }
  }
  solvers::sum_on_root(session.comm(), sum);
  NodalAverage a;
  if (session.rank() != 0) return a;
  a.stress.resize(N);
  a.stress_zz.resize(N);
  a.plastic_strain.resize(N);
  a.plastic.resize(N);
  for (int I = 0; I < N; ++I) {
    const double* s = sum.data() + static_cast<std::size_t>(kFields) * I;
    const double w = s[kFields - 1] > 0.0 ? 1.0 / s[kFields - 1] : 0.0;
    a.stress[I] = Vec3(s[0], s[1], s[2]) * w;
    a.stress_zz[I] = s[3] * w;
    a.plastic_strain[I] = s[4] * w;
    a.plastic[I] = s[5] * w;
  }
  return a;
}

} // namespace

NodalAverage nodal_average(const GalerkinModel& m, const PointStates& st,
                           const solvers::PetscSession& session) {
  return average(m, session, [&st](int k, double* v) {
    const double row[] = {st.stress[k](0),       st.stress[k](1),
                          st.stress[k](2),       st.stress_zz[k],
                          st.committed[k].alpha, static_cast<double>(st.plastic[k])};
    std::copy(row, row + 6, v);
  });
}

NodalAverage nodal_average(const GalerkinModel& m, const std::vector<Vec3>& stress,
                           const std::vector<double>& stress_zz,
                           const solvers::PetscSession& session) {
  return average(m, session, [&](int k, double* v) {
    const double row[] = {stress[k](0), stress[k](1), stress[k](2), stress_zz[k], 0.0, 0.0};
    std::copy(row, row + 6, v);
  });
}

} // namespace mf::implicit
