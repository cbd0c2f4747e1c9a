// A peridynamic step runs as one parallel region whose threads wait for each other by spinning
// when nothing in it has parallel loops of its own (pd::advance), else as a parallel region per
// loop: both paths give the same motion, broken bonds, s0 and energies bit for bit, on one
// thread and two, with held displacements, a held velocity, a body load, the LAMMPS rule,
// breaking bonds and the fracture account. And the spin barrier makes each phase's writes seen
// by every thread of the next.
#include "meshfree/pd/dynamics.hpp"
#include "meshfree/pd/spin_barrier.hpp"
#include <catch2/catch.hpp>
#include <omp.h>
#include <vector>

using namespace mf;

namespace {

constexpr double kDx = 0.5e-3;

struct Bar {
  pd::Model m;
  pd::BondState s;
  pd::Loading loading;
  pd::FractureEnergy fracture;
};

/// A 16 x 5 x 5 lattice (PMB with the LAMMPS rule, horizon 3 dx) held on its first two layers
/// (x at zero, y and z at a small imposed displacement), its last layer moving at a held
/// velocity along x and pulled by a body load: it stretches far enough to break bonds in 60
/// steps.
Bar bar() {
  Bar b;
  pd::Model& m = b.m;
  m.spacing = kDx;
  m.horizon = 3.0 * kDx;
  m.material_names = {"glass"};
  constexpr int nx = 16, ny = 5, nz = 5;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.particles.add({i * kDx, j * kDx, k * kDx}, kDx * kDx * kDx, 2200.0, 0);
  pd::LawTable t;
  t.materials = 1;
  materials::BondLaw law;
  law.c = 1.6863e22;
  law.critical_stretch = 5e-4;
  law.alpha = 0.25;
  t.laws = {law};
  t.law_of = {0};
  pd::build_bonds(m, t, pd::VolumeCorrection::Linear);
  b.s = pd::initial_state(m, {});
  pd::Constraint held, moving;
  held.name = "held";
  held.fixed[0] = held.fixed[1] = held.fixed[2] = true;
  held.value[1] = held.value[2] = 1e-7;
  moving.name = "moving";
  moving.velocity = true;
  moving.fixed[0] = true;
  moving.value[0] = 20.0;
  pd::BodyLoad pull;
  pull.name = "pull";
  pull.density = {1e12, 0.0, 0.0};
  for (int i = 0; i < m.particles.size(); ++i) {
    const double x = m.particles.reference(i).x();
    if (x < 1.5 * kDx) held.particles.push_back(i);
    if (x > (nx - 1.5) * kDx) moving.particles.push_back(i), pull.particles.push_back(i);
  }
  b.loading.constraints = {held, moving};
  b.loading.loads = {pull};
  return b;
}

struct Run {
  std::vector<double> u, v, a, s0;
  std::vector<unsigned char> intact;
  std::vector<pd::StepReport> steps;
};

/// 60 steps of the bar; with `far_impactor`, a fixed penalty sphere that never touches it, which
/// sends the step down the path of a region per loop.
Run run(bool far_impactor, int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Bar b = bar();
  std::vector<pd::Impactor> impactors;
  if (far_impactor) {
    pd::Impactor imp;
    imp.name = "far";
    imp.law = pd::Impactor::Law::Penalty;
    imp.stiffness = 1e17;
    imp.radius = kDx;
    imp.fixed = true;
    imp.position = {1.0, 1.0, 1.0};
    impactors.push_back(imp);
  }
  pd::Interactions x;
  x.impactors = &impactors;
  x.fracture = &b.fracture;
  const double dt = 0.5 * pd::stable_time_step(b.m);
  pd::accelerate(b.m, b.s, b.loading, x, true);
  Run r;
  for (int step = 0; step < 60; ++step)
    r.steps.push_back(pd::advance(b.m, b.s, b.loading, x, dt, step % 7 == 0));
  omp_set_num_threads(before);
  const particles::ParticleSet& q = b.m.particles;
  r.u = q.u, r.v = q.v, r.a = q.a, r.s0 = b.s.s0.committed, r.intact = b.s.intact;
  return r;
}

bool same_reports(const std::vector<pd::StepReport>& a, const std::vector<pd::StepReport>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].broken != b[k].broken || a[k].strain_energy != b[k].strain_energy ||
        a[k].external_work != b[k].external_work || a[k].contact_energy != b[k].contact_energy ||
        a[k].fracture_energy != b[k].fracture_energy || a[k].fracture_work != b[k].fracture_work)
      return false;
  return true;
}

long broken(const std::vector<pd::StepReport>& steps) {
  long n = 0;
  for (const pd::StepReport& s : steps) n += s.broken;
  return n;
}

} // namespace

TEST_CASE("a step in one parallel region equals a step of a region per loop bit for bit",
          "[pd][threads]") {
  for (int threads : {1, 2}) {
    INFO(threads << " thread(s)");
    const Run one = run(false, threads), many = run(true, threads);
    CHECK(broken(one.steps) > 0); // the bar breaks: the fracture account and s0 are exercised
    CHECK(one.u == many.u);
    CHECK(one.v == many.v);
    CHECK(one.a == many.a);
    CHECK(one.s0 == many.s0);
    CHECK(one.intact == many.intact);
    CHECK(same_reports(one.steps, many.steps));
  }
}

TEST_CASE("the spin barrier shows every thread the writes of the phase before it",
          "[pd][threads]") {
  constexpr int kThreads = 4, kPhases = 300;
  std::vector<int> slot(kThreads, -1);
  int stale = 0;
  pd::SpinBarrier barrier;
#pragma omp parallel num_threads(kThreads) reduction(+ : stale)
  {
    const int t = omp_get_thread_num(), T = omp_get_num_threads();
    for (int phase = 0; phase < kPhases; ++phase) {
      slot[t] = phase;
      barrier.wait();
      for (int q = 0; q < T; ++q) stale += slot[q] != phase;
      barrier.wait();
    }
  }
  CHECK(stale == 0);
}
