#pragma once
// What the static solvers of a peridynamic body share (pd/relaxation.hpp: adaptive dynamic
// relaxation in relaxation.cpp, Newton in statics.cpp): the loading per component, a guard that
// suspends breaking, and the net force with its norms.
#include "meshfree/pd/dynamics.hpp"
#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/state_based.hpp"
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace mf::pd::detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The loading of a static problem per component (3 per particle): the body force density, and
/// whether the component is held and where. Velocity-constrained components and, in a plane,
/// the out-of-plane ones are held where they are.
struct Statics {
  std::vector<double> b;
  std::vector<unsigned char> held;
  std::vector<double> target;
};

inline Statics statics(const Model& m, const Loading& loading) {
  const particles::ParticleSet& q = m.particles;
  const double t = q.time;
  const std::size_t size = 3 * static_cast<std::size_t>(q.size());
  Statics st;
  st.b.assign(size, 0.0);
  st.held.assign(size, 0);
  st.target = q.u;
  for (const BodyLoad& load : loading.loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const double g = loading.factor(load, k, t);
      for (int d = 0; d < 3; ++d) st.b[3 * load.particles[k] + d] += g * load.density_of(k, d);
    }
  loading.for_each_fixed(t, [&st](std::size_t k, const Constraint& c, double value) {
    st.held[k] = 1;
    if (!c.velocity) st.target[k] = value;
  });
  if (m.plane())
    for (std::size_t k = 2; k < size; k += 3) st.held[k] = 1;
  return st;
}

/// Suspends bond breaking for its lifetime: every critical stretch set to zero and the LAMMPS
/// rule's s0 put aside (the force loop then neither breaks bonds nor renews s0).
class NoBreaking {
public:
  NoBreaking(Model& m, BondState& s, bool active) : m_(m), s_(s), active_(active) {
    if (!active_) return;
    laws_ = m.laws;
    for (materials::BondLaw& law : m.laws) law.critical_stretch = 0.0;
    fold_laws(m);
    s0_ = std::move(s.s0);
    s.s0 = {};
  }
  ~NoBreaking() {
    if (!active_) return;
    m_.laws = std::move(laws_);
    fold_laws(m_);
    s_.s0 = std::move(s0_);
  }
  NoBreaking(const NoBreaking&) = delete;
  NoBreaking& operator=(const NoBreaking&) = delete;

private:
  Model& m_;
  BondState& s_;
  bool active_;
  std::vector<materials::BondLaw> laws_;
  particles::Staged<double> s0_;
};

/// Norms (squared) of the forces of one evaluation, each component's force density times its
/// particle's volume.
struct Norms {
  double residual = 0.0; // free components: bonds plus loads
  double loads = 0.0;    // free components: loads
  double reaction = 0.0; // held components: bonds
  double ratio() const {
    const double external = std::sqrt(std::max(loads, reaction));
    if (external > 0.0) return std::sqrt(residual) / external;
    return residual > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
};

/// Net force density f at the current displacement: the bond forces (pd::bond_forces, or the
/// state-based pd::state_forces) plus
/// `scale` times the body loads on free components, zero on held ones.
inline Norms net_force(const Model& m, BondState& s, const Statics& st, double scale,
                       std::vector<double>& y, std::vector<double>& f) {
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  y.resize(q.X.size());
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = q.X[k] + q.u[k];
  if (m.state_based())
    state_forces(m, s, y, f);
  else
    bond_forces(m, s, y, f);
  double residual = 0.0, loads = 0.0, reaction = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : residual, loads, reaction)
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
      const double V = q.volume[i];
      if (st.held[k]) {
        reaction += f[k] * V * f[k] * V;
        f[k] = 0.0;
      } else {
        const double load = scale * st.b[k];
        f[k] += load;
        residual += f[k] * V * f[k] * V;
        loads += load * V * load * V;
      }
    }
  return {residual, loads, reaction};
}

} // namespace mf::pd::detail
