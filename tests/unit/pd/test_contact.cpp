// Penalty impactors (LAMMPS fix indent) and the short-range contact of particles (LAMMPS
// peri/pmb) against their closed forms, and the energy and momentum they keep.
#include "meshfree/pd/dynamics.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;

namespace {

/// Two particles of a material with micromodulus c and horizon delta, too far apart for a bond.
pd::Model two_particles(double gap, double dx) {
  pd::Model m;
  m.dimension = materials::PdDimension::Solid3D;
  m.spacing = dx;
  m.horizon = 0.5 * dx; // no bond even at the gaps tested
  m.material_names = {"m"};
  m.particles.add({0.0, 0.0, 0.0}, dx * dx * dx, 2000.0, 0);
  m.particles.add({gap, 0.0, 0.0}, dx * dx * dx, 2000.0, 0);
  pd::LawTable t;
  t.materials = 1;
  materials::BondLaw law;
  law.c = 1e20;
  t.laws = {law};
  t.law_of = {0};
  pd::build_bonds(m, t, pd::VolumeCorrection::None);
  return m;
}

} // namespace

TEST_CASE("penalty impactor: LAMMPS fix indent's force and energy on a particle", "[pd][contact]") {
  // One particle 0.2 mm inside a sphere of radius 1 mm, 45 degrees off its axis:
  // force per volume K d^2 along the outward normal, energy V K d^3 / 3.
  pd::Model m = two_particles(1.0, 1e-3);
  const double K = 1e17, R = 1e-3, d = 2e-4, V = 1e-9;
  pd::Impactor imp;
  imp.law = pd::Impactor::Law::Penalty;
  imp.stiffness = K;
  imp.radius = R;
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  imp.position = -(R - d) * n; // particle 0 sits at the origin
  std::vector<double> y = m.particles.X, f(6, 0.0);
  pd::penalty_contact(m.particles, y, imp, f);
  CHECK(f[0] == Approx(K * d * d * n.x()).epsilon(1e-12));
  CHECK(f[1] == Approx(K * d * d * n.y()).epsilon(1e-12));
  CHECK(f[2] == 0.0);
  CHECK(f[3] == 0.0); // the other particle is outside
  CHECK((imp.contact_force + V * K * d * d * n).norm() < 1e-12 * V * K * d * d);
  CHECK(imp.contact_energy == Approx(V * K * d * d * d / 3.0).epsilon(1e-12));
}

TEST_CASE("penalty impactor: a free sphere bouncing off a particle keeps momentum and energy",
          "[pd][contact]") {
  pd::Model m = two_particles(1.0, 1e-3);
  m.particles.v[0] = 0.0;
  const double V = 1e-9, rho = 2000.0;
  std::vector<pd::Impactor> imp(1);
  imp[0].law = pd::Impactor::Law::Penalty;
  imp[0].stiffness = 1e17;
  imp[0].radius = 1e-3;
  imp[0].mass = 4e-6; // twice the particle's mass
  imp[0].position = {-1.05e-3, 0.0, 0.0};
  imp[0].velocity = {10.0, 0.0, 0.0};
  pd::BondState s = pd::initial_state(m, {});
  pd::Loading none;
  pd::Interactions x;
  x.impactors = &imp;
  pd::accelerate(m, s, none, x, false);
  const double e0 = imp[0].kinetic_energy();
  const double p0 = imp[0].mass * imp[0].velocity.x();
  double worst = 0.0;
  for (int step = 0; step < 4000; ++step) {
    const pd::StepReport r = pd::advance(m, s, none, x, 1e-8, true);
    const double e =
        imp[0].kinetic_energy() + pd::kinetic_energy(m) + r.contact_energy + r.strain_energy;
    worst = std::max(worst, std::abs(e - e0) / e0);
    const double p = imp[0].mass * imp[0].velocity.x() + rho * V * m.particles.v[0];
    CHECK(std::abs(p - p0) < 1e-12 * std::abs(p0));
  }
  // An elastic collision of masses 2m (10 m/s) and m (at rest): 10/3 and 40/3 m/s after it.
  CHECK(imp[0].velocity.x() == Approx(10.0 / 3.0).epsilon(1e-4));
  CHECK(m.particles.v[0] == Approx(40.0 / 3.0).epsilon(1e-4));
  CHECK(worst < 1e-4);
}

TEST_CASE("short-range contact: LAMMPS peri/pmb's repulsion of two particles", "[pd][contact]") {
  // d_ij = min(0.9 |X_i - X_j|, 1.35 lc) = 1.35 lc for particles 2 lc apart; pressed to r = lc
  // the force per volume on each is 15 c V (d_ij - r) / delta, apart, and the energy
  // 15 c V^2 (d_ij - r)^2 / (2 delta).
  const double lc = 1e-3, V = 1e-9;
  pd::Model m = two_particles(2.0 * lc, lc);
  pd::ShortRangeContact contact(m);
  std::vector<double> y = m.particles.X, f(6, 0.0);
  y[3] = lc;
  const double energy = contact.add_forces(m, y, f);
  const double expected = 15.0 * 1e20 * V * (0.35 * lc) / m.horizon;
  CHECK(f[0] == Approx(-expected).epsilon(1e-12));
  CHECK(f[3] == Approx(expected).epsilon(1e-12));
  CHECK(f[1] == 0.0);
  CHECK(energy ==
        Approx(15.0 * 1e20 * V * V * 0.35 * lc * 0.35 * lc / (2.0 * m.horizon)).epsilon(1e-12));
  // Apart beyond d_ij: nothing.
  y[3] = 1.36 * lc;
  std::fill(f.begin(), f.end(), 0.0);
  CHECK(contact.add_forces(m, y, f) == 0.0);
  CHECK(f[0] == 0.0);
  CHECK(contact.rebuilds() == 1); // moved by 0.36 lc < skin / 2: the list is kept
}
