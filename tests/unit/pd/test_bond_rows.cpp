// The packed bond rows (AVX2, AVX-512; pd/bond_rows.hpp) against the scalar rows, on every
// instruction set this processor has: forces, energy densities, strain energy, broken bonds,
// intact flags, plastic stretches and the LAMMPS rule's s0, bit for bit, over several
// evaluations of a lattice deformed far enough to break bonds, with a pre-crack, rows of ragged
// lengths (exact partial volumes reach past the horizon), both layouts, one law or two, the
// LAMMPS rule and micro-plasticity, with and without energies, on one thread and two.
#include "meshfree/pd/bond_rows.hpp"
#include "meshfree/pd/forces.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>
#include <omp.h>
#include <random>
#include <set>

using namespace mf;

namespace {

constexpr double kDx = 0.5e-3, kC = 1.6863e22;

struct Laws {
  const char* name;
  materials::BondLaw law;
  bool second_material; // a second law on a slab of the body, and an interface law
};

pd::LawTable table(const Laws& l) {
  pd::LawTable t;
  if (!l.second_material) {
    t.materials = 1, t.laws = {l.law}, t.law_of = {0};
    return t;
  }
  materials::BondLaw stiff = l.law, interface = l.law;
  stiff.c *= 3.0, stiff.critical_stretch *= 2.0;
  interface.c *= 2.0, interface.critical_stretch *= 0.7;
  t.materials = 2, t.laws = {l.law, stiff, interface}, t.law_of = {0, 2, 2, 1};
  return t;
}

/// An nx x ny x nz lattice (nz = 1: a plane) with horizon 3.3 dx and exact partial volumes.
pd::Model lattice(int nx, int ny, int nz, bool deterministic, const Laws& l) {
  pd::Model m;
  m.dimension = nz == 1 ? materials::PdDimension::PlaneStress : materials::PdDimension::Solid3D;
  m.spacing = kDx;
  m.horizon = 3.3 * kDx;
  m.material_names = {"a", "b"};
  m.deterministic = deterministic;
  const double volume = nz == 1 ? kDx * kDx * 1e-3 : kDx * kDx * kDx;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.particles.add({i * kDx, j * kDx, k * kDx}, volume, 2200.0,
                        l.second_material && j < ny / 3 ? 1 : 0);
  pd::build_bonds(m, table(l), pd::VolumeCorrection::Exact);
  return m;
}

/// Reference positions stretched along x by `stretch` plus a seeded random jitter.
std::vector<double> deformed(const pd::Model& m, double stretch, double jitter, int seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y = m.particles.X;
  for (int i = 0; i < m.particles.size(); ++i) {
    y[3 * i] *= 1.0 + stretch;
    for (int d = 0; d < (m.plane() ? 2 : 3); ++d) y[3 * i + d] += jitter * kDx * u(rng);
  }
  return y;
}

/// Everything an evaluation leaves.
struct Evaluation {
  std::vector<std::vector<double>> force, density;
  std::vector<double> energy;
  std::vector<long> broken;
  pd::BondState state;
};

/// Three evaluations (the s0 of one sets the limits of the next) at growing deformations.
Evaluation evaluate(const pd::Model& m, SimdTarget target, int threads, bool energy,
                    const std::vector<pd::PreCrack>& cracks) {
  mf::set_simd_target(target);
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  Evaluation e;
  e.state = pd::initial_state(m, cracks);
  for (int pass = 0; pass < 3; ++pass) {
    const std::vector<double> y = deformed(m, (1.0 + pass) * 3e-4, 2e-3, 11 + pass);
    std::vector<double> f, w;
    const pd::ForceReport r = pd::bond_forces(m, e.state, y, f, energy, energy ? &w : nullptr);
    e.force.push_back(f), e.density.push_back(w);
    e.energy.push_back(r.strain_energy), e.broken.push_back(r.broken);
  }
  omp_set_num_threads(before);
  mf::set_simd_target(mf::preferred_simd_target());
  return e;
}

/// The remainders of the rows' lengths by the packed groups' 4 bonds (a group past a row's end
/// repeats its last bond), and how many distinct lengths the rows have.
std::pair<std::set<long>, std::size_t> row_lengths(const pd::Model& m) {
  std::set<long> lengths, remainders;
  for (int i = 0; i < m.particles.owned_count(); ++i) {
    const long n = m.bonds.offset[i + 1] - m.bonds.offset[i];
    lengths.insert(n);
    remainders.insert(n % 4);
  }
  return {remainders, lengths.size()};
}

} // namespace

TEST_CASE("the packed bond rows equal the scalar rows bit for bit on every instruction set",
          "[pd][bonds][simd]") {
  const std::vector<SimdTarget> targets = mf::simd_targets();
  REQUIRE(targets.front() == SimdTarget::Baseline);
  std::cout << "bond rows compared on:";
  for (SimdTarget t : targets) std::cout << ' ' << mf::simd_target_name(t);
  std::cout << '\n';
  materials::BondLaw pmb, lammps, plastic;
  pmb.c = lammps.c = plastic.c = kC;
  pmb.critical_stretch = 6e-4;
  lammps.critical_stretch = 5e-4, lammps.alpha = 0.25;
  plastic.critical_stretch = 1.2e-3, plastic.yield_stretch = 3e-4;
  const std::vector<Laws> cases = {{"pmb", pmb, false},
                                   {"LAMMPS alpha rule", lammps, false},
                                   {"micro-plastic", plastic, false},
                                   {"two materials, LAMMPS rule", lammps, true},
                                   {"two materials, micro-plastic", plastic, true}};
  for (const Laws& l : cases)
    for (bool deterministic : {false, true})
      for (bool plane : {false, true}) {
        const pd::Model m = plane ? lattice(17, 13, 1, deterministic, l)
                                  : lattice(9, 8, 7, deterministic, l);
        // A crack across the middle of the body cuts bonds before the first evaluation.
        const double x = 4.5 * kDx;
        const pd::PreCrack crack{{x, -kDx, -kDx}, {x, 4.2 * kDx, -kDx}, {x, -kDx, 9 * kDx}};
        const auto [remainders, lengths] = row_lengths(m);
        CHECK(remainders == std::set<long>{0, 1, 2, 3}); // whole groups and every partial one
        CHECK(lengths >= 8);
        for (int threads : {1, 2})
          for (bool energy : {false, true}) {
            const Evaluation scalar =
                evaluate(m, SimdTarget::Baseline, threads, energy, {crack});
            long cut = 0;
            for (unsigned char b : pd::initial_state(m, {crack}).intact) cut += b == 0;
            CHECK(cut > 0);
            CHECK(scalar.broken[0] + scalar.broken[1] + scalar.broken[2] > 0);
            CHECK(scalar.broken[2] < m.bonds.directed / 2);
            for (SimdTarget t : targets) {
              INFO(l.name << (deterministic ? ", full rows" : ", half rows")
                          << (plane ? ", plane" : ", 3D") << ", " << threads << " thread(s)"
                          << (energy ? ", energies" : "") << ", " << mf::simd_target_name(t));
              const Evaluation packed = evaluate(m, t, threads, energy, {crack});
              CHECK(packed.force == scalar.force);
              CHECK(packed.density == scalar.density);
              CHECK(packed.energy == scalar.energy);
              CHECK(packed.broken == scalar.broken);
              CHECK(packed.state.intact == scalar.state.intact);
              CHECK(packed.state.plastic == scalar.state.plastic);
              CHECK(packed.state.s0.committed == scalar.state.s0.committed);
            }
          }
      }
}

TEST_CASE("the bond loop's instruction set is AVX2 where the processor has it, and can be set",
          "[pd][bonds][simd]") {
  const std::vector<SimdTarget> targets = mf::simd_targets();
  const bool avx2 =
      std::find(targets.begin(), targets.end(), SimdTarget::Avx2) != targets.end();
  CHECK(mf::simd_target() == (avx2 ? SimdTarget::Avx2 : SimdTarget::Baseline));
  for (SimdTarget t : targets) {
    mf::set_simd_target(t);
    CHECK(mf::simd_target() == t);
  }
  mf::set_simd_target(mf::preferred_simd_target());
}
