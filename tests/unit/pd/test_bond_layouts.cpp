// The bond storage of peridynamics: the class table of a lattice against its offsets, its
// two-byte indices and their widening past 65,536 classes, the half (each pair once) and full
// (global-id order) layouts against a direct sum of Silling & Askari's pairwise forces (a
// lattice, and a jittered cloud of a class a pair), the full layout's independence of threads and
// of which particles a rank owns (ghost partners), and the Morton order of the particles.
#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/particle_order.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <omp.h>
#include <random>
#include <set>

using namespace mf;

namespace {

constexpr double kDx = 0.5e-3, kHorizon = 3.0002 * kDx, kC = 1.6863e22;

/// An n^3 lattice; with `jitter` each particle moved by up to jitter dx along each axis (seeded),
/// so that no two bonds have the same length.
void add_lattice(particles::ParticleSet& p, int n, double jitter = 0.0) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-jitter * kDx, jitter * kDx);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        p.add({i * kDx + u(rng), j * kDx + u(rng), k * kDx + u(rng)}, kDx * kDx * kDx, 2200.0, 0);
}

pd::LawTable table(double s00, double alpha, double yield) {
  pd::LawTable t;
  t.materials = 1;
  materials::BondLaw law;
  law.c = kC;
  law.critical_stretch = s00;
  law.alpha = alpha;
  law.yield_stretch = yield;
  t.laws = {law};
  t.law_of = {0};
  return t;
}

pd::Model model(particles::ParticleSet p, bool deterministic, const pd::LawTable& t) {
  pd::Model m;
  m.spacing = kDx;
  m.horizon = kHorizon;
  m.material_names = {"glass"};
  m.particles = std::move(p);
  m.deterministic = deterministic;
  pd::build_bonds(m, t, pd::VolumeCorrection::Linear);
  return m;
}

/// Reference positions moved by a smooth field plus a random jitter (seeded).
std::vector<double> deformed(const particles::ParticleSet& p, double stretch, double jitter) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y = p.X;
  for (int i = 0; i < p.size(); ++i) {
    y[3 * i] *= 1.0 + stretch;
    for (int d = 0; d < 3; ++d) y[3 * i + d] += jitter * kDx * u(rng);
  }
  return y;
}

/// Direct sum over all pairs at positions y: f_i = sum_j c s w_ij e_ij, w_ij = V_j beta
/// (Silling & Askari 2005, eq. 3 and 6; beta the linear partial volume).
std::vector<double> pairwise_forces(const particles::ParticleSet& p, const std::vector<double>& y) {
  const int n = p.size();
  std::vector<double> direct(3 * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      const Vec3 xi = p.reference(j) - p.reference(i);
      const double L = xi.norm();
      if (L > kHorizon) continue;
      const double beta = L > kHorizon - 0.5 * kDx ? (kHorizon + 0.5 * kDx - L) / kDx : 1.0;
      const Vec3 d(y[3 * j] - y[3 * i], y[3 * j + 1] - y[3 * i + 1], y[3 * j + 2] - y[3 * i + 2]);
      const double s = (d.norm() - L) / L;
      for (int a = 0; a < 3; ++a)
        direct[3 * i + a] += kC * s * p.volume[j] * beta * d(a) / d.norm();
    }
  return direct;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    d = std::max(d, std::abs(a[k] - b[k]));
    s = std::max(s, std::abs(a[k]));
  }
  return d / s;
}

} // namespace

TEST_CASE("a lattice's bonds share one class per offset within the horizon", "[pd][bonds]") {
  particles::ParticleSet p;
  add_lattice(p, 9);
  const pd::Model m = model(p, false, table(0.0, 0.0, 0.0));
  // One class per length up to the round-off of the positions: the squared lengths |v|^2 <= 9
  // of integer offsets v are 1, 2, 3, 4, 5, 6, 8 and 9 (7 is no sum of three squares).
  std::set<long> squares;
  for (const pd::BondClass& c : m.bonds.classes) {
    const double n2 = c.length * c.length / (kDx * kDx);
    CHECK(std::abs(n2 - std::round(n2)) < 1e-9);
    squares.insert(std::lround(n2));
    // LAMMPS's vfrac_scale: (delta + dx/2 - |xi|) / dx beyond delta - dx/2 (pair_peri_pmb.cpp).
    const double beta =
        c.length > kHorizon - 0.5 * kDx ? (kHorizon + 0.5 * kDx - c.length) / kDx : 1.0;
    CHECK(c.weight == Approx(kDx * kDx * kDx * beta).epsilon(1e-14));
  }
  CHECK(squares == std::set<long>{1, 2, 3, 4, 5, 6, 8, 9});
  // Far fewer classes than bonds.
  CHECK(m.bonds.classes.size() < 1000);
  // Each pair once: a partner index above its row's particle; directed bonds twice the pairs.
  for (int i = 0; i < p.size(); ++i)
    for (long k = m.bonds.offset[i]; k < m.bonds.offset[i + 1]; ++k) CHECK(m.bonds.partner[k] > i);
  CHECK(m.bonds.directed == 2 * m.bonds.stored());
  // Partner 4 bytes, class 2, intact flag 1 a pair: 3.5 a directed bond and the rows' offsets.
  CHECK(m.bonds.cls.bytes_per_bond() == 2);
  CHECK(m.bonds.bytes(0) / m.bonds.directed < 4.0);
}

TEST_CASE("both bond layouts give Silling and Askari's pairwise forces", "[pd][bonds]") {
  particles::ParticleSet p;
  add_lattice(p, 7);
  const pd::LawTable t = table(0.0, 0.0, 0.0);
  const std::vector<double> y = deformed(p, 1e-4, 1e-3);
  const std::vector<double> direct = pairwise_forces(p, y);
  for (bool deterministic : {false, true}) {
    const pd::Model m = model(p, deterministic, t);
    pd::BondState s = pd::initial_state(m, {});
    std::vector<double> f;
    pd::bond_forces(m, s, y, f);
    CHECK(largest_difference(direct, f) < 1e-10);
  }
}

TEST_CASE("class indices past two bytes widen to four and keep every class", "[pd][bonds]") {
  pd::ClassIndices cls;
  cls.resize(5);
  for (long k = 0; k < 4; ++k) cls.set(k, static_cast<std::uint32_t>(65'532 + k));
  CHECK(cls.bytes_per_bond() == 2);
  CHECK(cls.view().narrow != nullptr);
  cls.set(4, 65'536);
  CHECK(cls.bytes_per_bond() == 4);
  CHECK(cls.view().wide != nullptr);
  CHECK(cls.view().narrow == nullptr);
  for (long k = 0; k < 5; ++k) {
    CHECK(cls[k] == 65'532 + k);
    CHECK(cls.view()[k] == 65'532 + k);
  }
}

TEST_CASE("a cloud of more bond classes than two bytes index gives the pairwise forces",
          "[pd][bonds]") {
  // A jittered lattice: every stored pair has a length of its own, so a class of its own.
  particles::ParticleSet p;
  add_lattice(p, 14, 0.05);
  const std::vector<double> y = deformed(p, 1e-4, 1e-3);
  const std::vector<double> direct = pairwise_forces(p, y);
  for (bool deterministic : {false, true}) {
    const pd::Model m = model(p, deterministic, table(0.0, 0.0, 0.0));
    INFO((deterministic ? "full rows" : "half rows")
         << ", " << m.bonds.classes.size() << " classes");
    CHECK(m.bonds.classes.size() > 65'536);
    CHECK(m.bonds.cls.bytes_per_bond() == 4);
    pd::BondState s = pd::initial_state(m, {});
    std::vector<double> f;
    pd::bond_forces(m, s, y, f);
    CHECK(largest_difference(direct, f) < 1e-10);
  }
}

TEST_CASE("the half and full layouts break the same bonds and renew the same s0", "[pd][bonds]") {
  particles::ParticleSet p;
  add_lattice(p, 8);
  for (double yield : {0.0, 2e-4}) {
    const pd::LawTable t = table(5e-4, 0.25, yield);
    const std::vector<double> y = deformed(p, 4e-4, 2e-3);
    pd::Model half = model(p, false, t), full = model(p, true, t);
    pd::BondState sh = pd::initial_state(half, {}), sf = pd::initial_state(full, {});
    std::vector<double> fh, ff;
    long broken = 0;
    for (int pass = 0; pass < 3; ++pass) { // s0 of one pass sets the limits of the next
      const pd::ForceReport rh = pd::bond_forces(half, sh, y, fh, true);
      const pd::ForceReport rf = pd::bond_forces(full, sf, y, ff, true);
      CHECK(rh.broken == rf.broken);
      CHECK(rh.strain_energy == Approx(rf.strain_energy).epsilon(1e-12));
      CHECK(largest_difference(ff, fh) < 1e-12);
      CHECK(largest_difference(sf.s0.committed, sh.s0.committed) < 1e-15);
      broken += rf.broken;
    }
    CHECK(broken > 0);
    std::vector<double> phi_h, phi_f;
    pd::damage(half, sh, phi_h);
    pd::damage(full, sf, phi_f);
    CHECK(largest_difference(phi_f, phi_h) < 1e-12);
  }
}

TEST_CASE("the full layout's forces depend neither on the threads nor on which particles are "
          "owned",
          "[pd][bonds]") {
  particles::ParticleSet whole;
  add_lattice(whole, 10);
  const pd::LawTable t = table(5e-4, 0.25, 0.0);
  const std::vector<double> y = deformed(whole, 3e-4, 2e-3);
  const pd::Model m = model(whole, true, t);
  std::vector<double> f1, f2;
  const int threads = omp_get_max_threads();
  {
    pd::BondState s = pd::initial_state(m, {});
    omp_set_num_threads(1);
    pd::bond_forces(m, s, y, f1);
    omp_set_num_threads(2);
    pd::BondState s2 = pd::initial_state(m, {});
    pd::bond_forces(m, s2, y, f2);
    omp_set_num_threads(threads);
  }
  CHECK(f1 == f2); // bit for bit
  // One "rank": the particles with x below the middle owned, copies of those within two
  // horizons above it as ghosts (in an order of their own), the global ids kept.
  const double cut = 4.7 * kDx;
  particles::ParticleSet part;
  std::vector<int> global;
  for (int i = 0; i < whole.size(); ++i)
    if (whole.X[3 * i] < cut) {
      const int k = part.add(whole.reference(i), whole.volume[i], whole.density[i], 0);
      part.id[k] = whole.id[i];
      global.push_back(i);
    }
  for (int i = whole.size() - 1; i >= 0; --i)
    if (whole.X[3 * i] >= cut && whole.X[3 * i] < cut + 2.0 * kHorizon) {
      const int g = part.add_ghost(0);
      for (int d = 0; d < 3; ++d) part.X[3 * g + d] = whole.X[3 * i + d];
      part.id[g] = whole.id[i];
      global.push_back(i);
    }
  std::vector<double> yp(3 * part.size());
  for (int k = 0; k < part.size(); ++k)
    for (int d = 0; d < 3; ++d) yp[3 * k + d] = y[3 * global[k] + d];
  for (bool deterministic : {true, false}) {
    const pd::Model mp = model(part, deterministic, t);
    pd::BondState s = pd::initial_state(mp, {});
    std::vector<double> fp;
    pd::bond_forces(mp, s, yp, fp);
    double worst = 0.0, scale = 0.0;
    for (int k = 0; k < part.owned_count(); ++k)
      for (int d = 0; d < 3; ++d) {
        worst = std::max(worst, std::abs(fp[3 * k + d] - f1[3 * global[k] + d]));
        scale = std::max(scale, std::abs(f1[3 * global[k] + d]));
      }
    if (deterministic)
      CHECK(worst == 0.0); // bit for bit
    else
      CHECK(worst < 1e-12 * scale);
  }
}

TEST_CASE("Morton keys interleave the cell indices and the order is a permutation", "[pd][bonds]") {
  const double lo[3] = {0.0, 0.0, 0.0};
  const auto key = [&](double i, double j, double k) {
    const double x[3] = {i, j, k};
    return pd::morton_key(x, lo, 1.0);
  };
  CHECK(key(1, 0, 0) == 1);
  CHECK(key(0, 1, 0) == 2);
  CHECK(key(0, 0, 1) == 4);
  CHECK(key(3, 0, 0) == 9);  // x bits 0, 1 at 0, 3
  CHECK(key(2, 3, 1) == 30); // x bit 1 -> 3; y bits 0, 1 -> 1, 4; z bit 0 -> 2
  CHECK(key(0, 0, 1 << 20) == 1ull << 62);
  particles::ParticleSet p;
  add_lattice(p, 4);
  const particles::ParticleSet before = p;
  const std::vector<int> order = pd::order_along_curve(p, kDx);
  std::vector<int> seen(order.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    ++seen[order[k]];
    CHECK(p.id[k] == static_cast<long>(k));
    CHECK((p.reference(k) - before.reference(order[k])).norm() == 0.0);
  }
  CHECK(std::count(seen.begin(), seen.end(), 1) == p.size());
  // The first 8 particles are the first 2 x 2 x 2 block of the lattice.
  for (int k = 0; k < 8; ++k) CHECK(p.reference(k).maxCoeff() < 1.5 * kDx);
}
