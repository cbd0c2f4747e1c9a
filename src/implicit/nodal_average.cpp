#include "meshfree/implicit/nodal_average.hpp"
#include "meshfree/implicit/nodal_sums.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>

namespace mf::implicit {

namespace {

/// `value(k, v)` writes row k's sxx, syy, sxy, szz, alpha and plastic flag into v.
template <class Value>
NodalAverage average(const GalerkinModel& m, const solvers::PetscSession& session, Value value) {
  constexpr int kFields = 6;
  const std::vector<double> s = nodal_averages<kFields>(m, session, value);
  NodalAverage a;
  if (session.rank() != 0) return a;
  const int N = m.node_count();
  a.stress.resize(N);
  a.stress_zz.resize(N);
  a.plastic_strain.resize(N);
  a.plastic.resize(N);
  for (int I = 0; I < N; ++I) {
    const double* v = s.data() + static_cast<std::size_t>(kFields) * I;
    a.stress[I] = Vec3(v[0], v[1], v[2]);
    a.stress_zz[I] = v[3];
    a.plastic_strain[I] = v[4];
    a.plastic[I] = v[5];
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
