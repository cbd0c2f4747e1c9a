#pragma once
// LPS bodies for the state-based tests: a lattice (or a body cut from one) of one elastic
// material, and its positions under a displacement field.
#include "meshfree/pd/model.hpp"
#include "meshfree/pd/state_based.hpp"
#include <functional>
#include <vector>

namespace mf::test {

using materials::PdDimension;

struct Elastic {
  double E = 0.0, nu = 0.0;
  double K() const { return E / (3.0 * (1.0 - 2.0 * nu)); }
  double mu() const { return E / (2.0 * (1.0 + nu)); }
  double lambda() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
};

/// A uniform LPS lattice of nx x ny (x nz) particles of spacing dx, one material; `keep(X)`
/// (when given) keeps the particles of a body cut from it.
inline pd::Model lps_lattice(PdDimension dim, int nx, int ny, int nz, double dx, double m_factor,
                             const Elastic& el, double density, pd::VolumeCorrection correction,
                             materials::Influence influence = materials::Influence::InverseLength,
                             bool deterministic = false,
                             const std::function<bool(const Eigen::Vector3d&)>& keep = {}) {
  pd::Model m;
  m.dimension = dim;
  m.thickness = 0.01;
  m.spacing = dx;
  m.horizon = m_factor * dx;
  m.deterministic = deterministic;
  m.material_names = {"solid"};
  const bool plane = dim != PdDimension::Solid3D;
  const double volume = plane ? dx * dx * m.thickness : dx * dx * dx;
  for (int k = 0; k < (plane ? 1 : nz); ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (!keep || keep(Eigen::Vector3d(i * dx, j * dx, plane ? 0.0 : k * dx)))
          m.particles.add({i * dx, j * dx, plane ? 0.0 : k * dx}, volume, density, 0);
  const materials::LpsLaw law = materials::lps_law(dim, el.K(), el.mu());
  m.lps = {law};
  m.influence = influence;
  pd::LawTable t;
  t.materials = 1;
  materials::BondLaw bond;
  bond.c = materials::lps_contact_micromodulus(dim, law, m.horizon, m.thickness);
  t.laws = {bond};
  t.law_of = {0};
  pd::build_bonds(m, t, correction);
  pd::set_weighted_volumes(m, pd::initial_state(m, {}));
  return m;
}

/// Positions X + u(X).
template <class U> std::vector<double> deformed(const pd::Model& m, U&& u) {
  std::vector<double> y = m.particles.X;
  for (int i = 0; i < m.particles.size(); ++i) {
    const Eigen::Vector3d d = u(m.particles.reference(i));
    for (int e = 0; e < 3; ++e) y[3 * i + e] += d(e);
  }
  return y;
}

} // namespace mf::test
