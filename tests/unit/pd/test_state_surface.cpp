// The position-aware influence of the LPS (pd/state_surface.hpp): every particle's dilatation and
// energy density are the continuum's for every homogeneous strain, at faces, edges, corners and
// curved surfaces, where the LPS's are not; the forces are the energy's gradient, bonds broken or
// not (both layouts and thread counts: test_state_based.cpp's layouts test).
#include "meshfree/pd/state_based.hpp"
#include "meshfree/pd/state_surface.hpp"
#include "pd/lps_body.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>
#include <random>

using namespace mf;
using materials::PdDimension;
using namespace mf::test; // lps_lattice, deformed, Elastic

namespace {

struct Body {
  const char* name;
  PdDimension dim;
  int nx, ny, nz;
  double horizon; // in spacings
  double nu;
  materials::Influence influence;
  pd::VolumeCorrection correction;
  double ball; // > 0: the disk or ball of this radius (in spacings) cut from the lattice
};

const double kDx = 1e-3;

pd::Model body_of(const Body& b, bool full = false) {
  const double c = 0.5 * (b.nx - 1) * kDx, r = b.ball * kDx;
  const auto inside = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d centre(c, c, b.dim == PdDimension::Solid3D ? c : 0.0);
    return (x - centre).norm() <= r;
  };
  return lps_lattice(b.dim, b.nx, b.ny, b.nz, kDx, b.horizon, Elastic{70e9, b.nu}, 2700.0,
                     b.correction, b.influence, full,
                     b.ball > 0.0 ? std::function<bool(const Eigen::Vector3d&)>(inside)
                                  : std::function<bool(const Eigen::Vector3d&)>());
}

/// A random symmetric strain of size 1e-5 (in-plane in a plane), fixed by `seed`.
Eigen::Matrix3d random_strain(std::mt19937& rng, bool plane) {
  std::uniform_real_distribution<double> u(-1e-5, 1e-5);
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  for (int a = 0; a < (plane ? 2 : 3); ++a)
    for (int b = a; b < (plane ? 2 : 3); ++b) e(a, b) = e(b, a) = u(rng);
  return e;
}

/// The continuum's energy density of strain e: lambda tr^2 / 2 + mu e : e, with the plane
/// stress lambda in plane stress.
double continuum_energy(PdDimension dim, const Elastic& el, const Eigen::Matrix3d& e) {
  const double mu = el.mu();
  const double lambda =
      dim == PdDimension::PlaneStress ? 2 * el.lambda() * mu / (el.lambda() + 2 * mu) : el.lambda();
  return 0.5 * lambda * e.trace() * e.trace() + mu * (e.array() * e.array()).sum();
}

/// Largest relative error over the particles of the dilatation (of |e|) and of the energy
/// density under u = e x, the odd and even parts of +e and -e taken so that what remains is the
/// linear response.
std::pair<double, double> homogeneous_errors(const pd::Model& m, const Body& b,
                                             const Eigen::Matrix3d& e) {
  std::vector<double> f, w[2], theta[2];
  for (int sign = 0; sign < 2; ++sign) {
    pd::BondState s = pd::initial_state(m, {});
    const Eigen::Matrix3d g = sign ? Eigen::Matrix3d(-e) : e;
    pd::state_forces(m, s, deformed(m, [&](const Eigen::Vector3d& x) { return g * x; }), f, true,
                     &w[sign], &theta[sign]);
  }
  const double exact_w = continuum_energy(b.dim, Elastic{70e9, b.nu}, e);
  double dil = 0.0, energy = 0.0;
  for (int i = 0; i < m.particles.owned_count(); ++i) {
    dil = std::max(dil, std::abs(0.5 * (theta[0][i] - theta[1][i]) - e.trace()) / e.norm());
    energy = std::max(energy, std::abs(0.5 * (w[0][i] + w[1][i]) - exact_w) / exact_w);
  }
  return {dil, energy};
}

const std::vector<Body>& bodies() {
  using I = materials::Influence;
  using V = pd::VolumeCorrection;
  static const std::vector<Body> table = {
      {"3D block", PdDimension::Solid3D, 7, 6, 5, 3.0, 0.3, I::InverseLength, V::Exact, 0.0},
      {"3D block, Gaussian, delta 2.5 dx", PdDimension::Solid3D, 7, 7, 6, 2.5, 0.2, I::Gaussian,
       V::Linear, 0.0},
      {"3D ball", PdDimension::Solid3D, 11, 11, 11, 3.0, 0.3, I::InverseLength, V::Exact, 4.6},
      {"plane strain block", PdDimension::PlaneStrain, 16, 11, 1, 3.0, 0.3, I::InverseLength,
       V::Exact, 0.0},
      {"plane stress block, constant, delta 4 dx", PdDimension::PlaneStress, 15, 12, 1, 4.0, 0.2,
       I::Constant, V::Exact, 0.0},
      {"plane strain disk", PdDimension::PlaneStrain, 17, 17, 1, 3.0, 0.3, I::InverseLength,
       V::None, 7.3},
  };
  return table;
}

} // namespace

TEST_CASE("position-aware LPS: every particle's dilatation and energy density are the "
          "continuum's for any homogeneous strain, at faces, edges, corners and curves",
          "[pd][lps][surface]") {
  std::mt19937 rng(20261207);
  for (const Body& b : bodies()) {
    const bool plane = b.dim != PdDimension::Solid3D;
    const pd::Model lps = body_of(b);
    pd::Model aware = body_of(b);
    CHECK(pd::apply_position_aware_influence(aware, pd::initial_state(aware, {})) == 0);
    double worst[2][2] = {{0, 0}, {0, 0}};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d e = random_strain(rng, plane);
      const auto [d0, w0] = homogeneous_errors(lps, b, e);
      const auto [d1, w1] = homogeneous_errors(aware, b, e);
      worst[0][0] = std::max(worst[0][0], d0), worst[0][1] = std::max(worst[0][1], w0);
      worst[1][0] = std::max(worst[1][0], d1), worst[1][1] = std::max(worst[1][1], w1);
    }
    std::cout << "position-aware, " << b.name << " (" << aware.particles.size() << " particles, "
              << aware.bonds.classes.size() << " classes): dilatation " << worst[1][0]
              << ", energy " << worst[1][1] << " (LPS " << worst[0][0] << ", " << worst[0][1]
              << ")\n";
    INFO(b.name);
    CHECK(worst[1][0] < 1e-8);
    CHECK(worst[1][1] < 1e-7);
    // The LPS's own surface error, which the influence removes.
    CHECK(worst[0][1] > 0.05);
  }
}

TEST_CASE("position-aware LPS: the force is the gradient of the energy, bonds broken or not",
          "[pd][lps][surface]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Body& b : {bodies()[0], bodies()[3], bodies()[5]}) {
    pd::Model m = body_of(b);
    REQUIRE(pd::apply_position_aware_influence(m, pd::initial_state(m, {})) == 0);
    const int n = m.particles.size();
    // A smooth field of 1e-4 and a random direction of 1e-9 spacings.
    const std::vector<double> y = deformed(m, [](const Eigen::Vector3d& x) {
      return Eigen::Vector3d(0.1 * x.x() * x.y(), -0.05 * x.x() * x.x(), 0.02 * x.y() * x.z());
    });
    std::vector<double> dir(3 * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int e = 0; e < (m.plane() ? 2 : 3); ++e) dir[3 * i + e] = u(rng);
    for (int cut : {0, 7}) {
      std::vector<unsigned char> intact(m.bonds.stored(), 1);
      if (cut)
        for (long k = 0; k < m.bonds.stored(); k += cut) intact[k] = 0;
      const auto energy = [&](double h, std::vector<double>* force) {
        std::vector<double> z = y, f, w;
        for (std::size_t k = 0; k < z.size(); ++k) z[k] += h * dir[k];
        pd::state_forces_kept(m, intact, {}, z, f, w);
        if (force) *force = f;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) sum += m.particles.volume[i] * w[i];
        return sum;
      };
      std::vector<double> f;
      energy(0.0, &f);
      double work = 0.0, scale = 0.0;
      for (int i = 0; i < n; ++i)
        for (int e = 0; e < 3; ++e) {
          work -= m.particles.volume[i] * f[3 * i + e] * dir[3 * i + e];
          scale += std::abs(m.particles.volume[i] * f[3 * i + e] * dir[3 * i + e]);
        }
      const double h = 1e-7 * kDx; // round-off 1e-10 of the terms here, 1e-7 at 1e-9 dx
      const double slope = (energy(h, nullptr) - energy(-h, nullptr)) / (2.0 * h);
      std::cout << "position-aware, " << b.name << (cut ? ", every 7th bond cut" : "") << ": dE/dh "
                << slope << " against -f . dir " << work << " (of "
                << std::abs(slope - work) / scale << " the sum of |terms|)\n";
      INFO(b.name << ", cut " << cut);
      CHECK(std::abs(slope - work) < 1e-8 * scale);
    }
  }
}
