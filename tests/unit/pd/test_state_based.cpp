// State-based peridynamics (LPS): the moduli of the discrete body against the continuum for
// Poisson's ratios bond-based peridynamics cannot have (3D, plane strain, plane stress, three
// influence functions), the wave speeds, the layouts and threads, the stable step against the
// linearised body's highest frequency, energy conservation, breaking, and the critical stretch.
#include "energy_drift.hpp"
#include "lammps_lattice.hpp"
#include "meshfree/pd/dynamics.hpp"
#include "meshfree/pd/relaxation.hpp"
#include "meshfree/pd/state_based.hpp"
#include "meshfree/pd/state_surface.hpp"
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "pd/lps_body.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <cmath>
#include <iostream>
#include <omp.h>

using namespace mf;
using materials::PdDimension;
using namespace mf::test; // lps_lattice, deformed, Elastic

namespace {

/// Strain energy density at particle `centre` under u = G x.
double energy_density(const pd::Model& m, int centre, const Eigen::Matrix3d& G) {
  pd::BondState s = pd::initial_state(m, {});
  std::vector<double> f, w;
  pd::state_forces(m, s, deformed(m, [&](const Eigen::Vector3d& x) { return G * x; }), f, true, &w);
  return w[centre];
}

int centre_of(PdDimension dim, int n) {
  const int h = n / 2;
  return dim == PdDimension::Solid3D ? (h * n + h) * n + h : h * n + h;
}

/// The continuum's energy densities of a uniaxial strain eps, a shear strain gamma = eps and a
/// dilatation eps I (in-plane in 2D): (lambda + 2 mu) eps^2 / 2, mu eps^2 / 2 and d kappa_eff
/// eps^2 / 2, with the plane stress constants in plane stress.
struct Continuum {
  double uniaxial, shear, dilatation;
};

Continuum continuum(PdDimension dim, const Elastic& el, double eps) {
  const double e2 = 0.5 * eps * eps, mu = el.mu();
  if (dim == PdDimension::Solid3D) return {(el.lambda() + 2 * mu) * e2, mu * e2, 9.0 * el.K() * e2};
  const double lambda =
      dim == PdDimension::PlaneStress ? 2 * el.lambda() * mu / (el.lambda() + 2 * mu) : el.lambda();
  return {(lambda + 2 * mu) * e2, mu * e2, 4.0 * (lambda + mu) * e2};
}

} // namespace

TEST_CASE("LPS gives the continuum moduli of any Poisson's ratio away from the surface",
          "[pd][lps]") {
  // The interior particle's energy density under a uniaxial strain, a shear and a dilatation
  // gives C11, C44 and the bulk modulus of the discrete body (a cubic lattice has three
  // moduli); each within 1% of the continuum's, so the stress C : eps is within 1% too: in 3D
  // with a horizon of 3 spacings, in a plane with 5 (at 3 the square lattice's fourth moments
  // leave C44 2.6% low and C11 0.7-1.0% high; at 4, 1.0% and 0.3%).
  const double eps = 1e-6;
  struct Case {
    PdDimension dim;
    double nu;
    materials::Influence influence;
    double horizon; // spacings
    double tolerance;
  };
  using I = materials::Influence;
  const Case cases[] = {{PdDimension::Solid3D, 0.3, I::InverseLength, 3.0, 0.01},
                        {PdDimension::Solid3D, 0.2, I::InverseLength, 3.0, 0.01},
                        {PdDimension::Solid3D, 0.3, I::Constant, 3.0, 0.01},
                        {PdDimension::Solid3D, 0.3, I::Gaussian, 3.0, 0.01},
                        {PdDimension::PlaneStrain, 0.3, I::InverseLength, 5.0, 0.01},
                        {PdDimension::PlaneStrain, 0.2, I::InverseLength, 5.0, 0.01},
                        {PdDimension::PlaneStress, 0.3, I::InverseLength, 5.0, 0.01},
                        {PdDimension::PlaneStress, 0.2, I::Constant, 5.0, 0.01},
                        {PdDimension::PlaneStrain, 0.3, I::InverseLength, 3.0, 0.03}};
  for (const Case& c : cases) {
    const Elastic el{70e9, c.nu};
    const bool plane = c.dim != PdDimension::Solid3D;
    const int n = 2 * static_cast<int>(c.horizon) + 5;
    const pd::Model m = lps_lattice(c.dim, n, n, n, 1e-3, c.horizon, el, 2700.0,
                                    pd::VolumeCorrection::Exact, c.influence);
    const int centre = centre_of(c.dim, n);
    const Continuum ref = continuum(c.dim, el, eps);
    Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
    G(0, 0) = eps;
    const double uniaxial = energy_density(m, centre, G) / ref.uniaxial;
    G.setZero();
    G(0, 1) = eps;
    const double shear = energy_density(m, centre, G) / ref.shear;
    G = eps * Eigen::Matrix3d::Identity();
    if (plane) G(2, 2) = 0.0;
    const double dilatation = energy_density(m, centre, G) / ref.dilatation;
    std::cout << "lps moduli, dimension " << static_cast<int>(c.dim) << ", nu " << c.nu
              << ", influence " << static_cast<int>(c.influence) << ", horizon " << c.horizon
              << " dx: C11 " << uniaxial << ", C44 " << shear << ", bulk " << dilatation
              << " of the continuum\n";
    CHECK(std::abs(uniaxial - 1.0) < c.tolerance);
    CHECK(std::abs(shear - 1.0) < c.tolerance);
    CHECK(std::abs(dilatation - 1.0) < 1e-6); // the weighted volume makes it exact
  }
}

TEST_CASE("LPS waves travel at the continuum's P- and S-wave speeds", "[pd][lps]") {
  // The acceleration of the middle particle of a long body under u = A cos(k (x - x_c)) along
  // x (P) or y (S), a = -c^2 k^2 A, with a wavelength of 20 horizons: c within 1% of
  // sqrt((lambda + 2 mu) / rho) and sqrt(mu / rho) (plane stress: lambda of plane stress).
  const double rho = 7850.0, dx = 1e-3, A = 1e-9;
  const Elastic el{200e9, 0.3};
  for (PdDimension dim :
       {PdDimension::Solid3D, PdDimension::PlaneStrain, PdDimension::PlaneStress}) {
    const bool plane = dim != PdDimension::Solid3D;
    const double horizon = plane ? 5.0 : 3.0;
    const int nx = static_cast<int>(40 * horizon) + 1, ny = 2 * static_cast<int>(horizon) + 5;
    const pd::Model m =
        lps_lattice(dim, nx, ny, ny, dx, horizon, el, rho, pd::VolumeCorrection::Exact);
    const int h = ny / 2;
    const int centre = plane ? h * nx + nx / 2 : (h * ny + h) * nx + nx / 2;
    const double xc = (nx / 2) * dx, k = 2.0 * M_PI / (20.0 * horizon * dx);
    const double mu = el.mu();
    const double lambda = dim == PdDimension::PlaneStress
                              ? 2 * el.lambda() * mu / (el.lambda() + 2 * mu)
                              : el.lambda();
    const double speeds[2] = {std::sqrt((lambda + 2 * mu) / rho), std::sqrt(mu / rho)};
    for (int axis = 0; axis < 2; ++axis) {
      pd::BondState s = pd::initial_state(m, {});
      std::vector<double> f;
      pd::state_forces(m, s,
                       deformed(m,
                                [&](const Eigen::Vector3d& x) {
                                  Eigen::Vector3d u = Eigen::Vector3d::Zero();
                                  u(axis) = A * std::cos(k * (x.x() - xc));
                                  return u;
                                }),
                       f);
      const double c = std::sqrt(-f[3 * centre + axis] / rho / (k * k * A));
      std::cout << "lps wave, dimension " << static_cast<int>(dim) << (axis ? ", S: " : ", P: ")
                << c << " m/s against " << speeds[axis] << " (ratio " << c / speeds[axis] << ")\n";
      CHECK(std::abs(c / speeds[axis] - 1.0) < 0.01);
    }
  }
}

TEST_CASE("LPS: both layouts give the same forces and breaks, the full one whatever the threads",
          "[pd][lps]") {
  // The LPS, and the LPS with its position-aware influence (pd/state_surface.hpp).
  const Elastic el{70e9, 0.3};
  for (const bool aware : {false, true}) {
    const auto run = [&](bool full, int threads, long& broken) {
      pd::Model m =
          lps_lattice(PdDimension::Solid3D, 9, 8, 7, 1e-3, 3.0, el, 2700.0,
                      pd::VolumeCorrection::Exact, materials::Influence::InverseLength, full);
      m.laws[0].critical_stretch = 2.0e-3;
      pd::fold_laws(m);
      pd::BondState s = pd::initial_state(m, {});
      if (aware) REQUIRE(pd::apply_position_aware_influence(m, s) == 0);
      // A stretch that grows along x and a twist: bonds in the right part break.
      const std::vector<double> y = deformed(m, [](const Eigen::Vector3d& x) {
        return Eigen::Vector3d(0.3 * x.x() * x.x(), 0.02 * x.x() * x.z(), -0.02 * x.x() * x.y());
      });
      std::vector<double> f;
      const int before = omp_get_max_threads();
      omp_set_num_threads(threads);
      broken = pd::state_forces(m, s, y, f).broken;
      omp_set_num_threads(before);
      return f;
    };
    long b_half = 0, b_full1 = 0, b_full2 = 0, b_half2 = 0;
    const std::vector<double> half = run(false, 1, b_half), half2 = run(false, 2, b_half2);
    const std::vector<double> full1 = run(true, 1, b_full1), full2 = run(true, 2, b_full2);
    INFO("position-aware " << aware);
    REQUIRE(b_half > 0);
    CHECK(b_half == b_full1);
    CHECK(b_half2 == b_half);
    CHECK(full1 == full2); // bit for bit
    double scale = 0.0, diff = 0.0, diff2 = 0.0;
    for (std::size_t k = 0; k < half.size(); ++k) {
      scale = std::max(scale, std::abs(full1[k]));
      diff = std::max(diff, std::abs(half[k] - full1[k]));
      diff2 = std::max(diff2, std::abs(half2[k] - full1[k]));
    }
    std::cout << "lps" << (aware ? " position-aware" : "") << " layouts: " << b_half
              << " bonds broken, half - full " << diff / scale << " (1 thread), " << diff2 / scale
              << " (2 threads)\n";
    CHECK(diff < 1e-12 * scale);
    CHECK(diff2 < 1e-12 * scale);
  }
}

TEST_CASE("LPS: the stable step is the linearised body's 2 / omega_max", "[pd][lps]") {
  // The stiffness of a small free body by central differences of the forces; its highest
  // frequency from the eigenvalues of K / rho, against the power iteration's estimate (which
  // approaches it from above).
  const double rho = 2700.0;
  for (PdDimension dim : {PdDimension::Solid3D, PdDimension::PlaneStrain}) {
    for (double nu : {0.125, 0.2, 0.3, 0.45}) {
      const Elastic el{70e9, nu};
      const bool plane = dim != PdDimension::Solid3D;
      const pd::Model m = lps_lattice(dim, plane ? 9 : 5, plane ? 9 : 5, 5, 1e-3, 3.0, el, rho,
                                      pd::VolumeCorrection::Exact);
      const int n = m.particles.size(), dims = plane ? 2 : 3;
      Eigen::MatrixXd K(dims * n, dims * n);
      const double h = 1e-9;
      for (int i = 0; i < n; ++i)
        for (int d = 0; d < dims; ++d) {
          std::vector<double> fp, fm;
          std::vector<double> y = m.particles.X;
          y[3 * i + d] += h;
          pd::BondState s = pd::initial_state(m, {});
          pd::state_forces(m, s, y, fp);
          y[3 * i + d] -= 2 * h;
          pd::state_forces(m, s, y, fm);
          for (int j = 0; j < n; ++j)
            for (int e = 0; e < dims; ++e)
              K(dims * j + e, dims * i + d) = -(fp[3 * j + e] - fm[3 * j + e]) / (2 * h);
        }
      const Eigen::MatrixXd Ks = 0.5 * (K + K.transpose());
      const double lambda_max =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ks / rho).eigenvalues().maxCoeff();
      const double exact = 2.0 / std::sqrt(lambda_max);
      const double estimate = pd::state_stable_time_step(m);
      std::cout << "lps stable step, dimension " << static_cast<int>(dim) << ", nu " << nu
                << ": power iteration " << estimate << " s, 2 / omega_max " << exact << " s (ratio "
                << estimate / exact << ")\n";
      CHECK(estimate >= exact * (1.0 - 1e-6));
      CHECK(estimate < 1.02 * exact);
    }
  }
}

TEST_CASE("LPS: velocity Verlet keeps the energy of a free vibrating block", "[pd][lps]") {
  const Elastic el{70e9, 0.3};
  pd::Model m = lps_lattice(PdDimension::Solid3D, 8, 7, 6, 1e-3, 3.0, el, 2700.0,
                            pd::VolumeCorrection::Exact);
  for (int i = 0; i < m.particles.size(); ++i) {
    const Eigen::Vector3d x = m.particles.reference(i);
    m.particles.v[3 * i] = 0.5 * std::sin(M_PI * x.x() / 7e-3);
    m.particles.v[3 * i + 1] = 0.3 * std::sin(M_PI * x.z() / 5e-3);
  }
  pd::BondState s = pd::initial_state(m, {});
  // As for bond-based bodies, E oscillates within O(dt^2) and does not drift. Measured on this
  // block over 4000 steps: max |E - E0| / E0 = 9.0e-2 at 0.8 of the limit 2 / omega_max, 2.4e-2
  // at 0.5, 8.7e-4 at 0.1: the corner particles' small weighted volumes make them stiff, and
  // the smooth field moves them at their own high frequencies.
  const test::EnergyDrift d = test::energy_drift(m, s, 0.1 * pd::state_stable_time_step(m), 4000, 20);
  const double worst = d.worst, first = d.first, last = d.last;
  std::cout << "lps energy: largest |E - E0| / E0 over 4000 steps " << worst << " (first thousand "
            << first << ", last thousand " << last << ")\n";
  CHECK(worst < 2e-3);
  CHECK(std::abs(last - first) < 0.2 * first);
}

TEST_CASE("LPS critical stretch equals the bond-based one where the two models coincide",
          "[pd][lps]") {
  const double E = 70e9, G0 = 100.0, delta = 3e-3;
  for (PdDimension dim :
       {PdDimension::Solid3D, PdDimension::PlaneStrain, PdDimension::PlaneStress}) {
    const double nu = materials::pd_poisson_ratio(dim);
    const Elastic el{E, nu};
    const materials::LpsLaw law = materials::lps_law(dim, el.K(), el.mu());
    CHECK(materials::lps_critical_stretch(dim, law, G0, delta) ==
          Approx(materials::pd_critical_stretch(dim, E, G0, delta)).epsilon(1e-12));
    // Its contact micromodulus is the bond-based micromodulus of the same modulus.
    CHECK(materials::lps_contact_micromodulus(dim, law, delta, 0.01) ==
          Approx(materials::pd_micromodulus(dim, E, delta, 0.01)).epsilon(1e-12));
  }
}

TEST_CASE("LPS on a lattice matches LAMMPS peri/lps step for step", "[pd][lps]") {
  // reference/lammps/lps_lattice: LAMMPS's peri/lps on a 40 x 6 x 6 bar of a simple cubic lattice
  // (a = 0.5 mm), K = 25 GPa, G = 11.538 GPa (E = 30 GPa, nu = 0.3), delta = 0.0015001, s00 = 1,
  // alpha = 0.25, density 2200, a smooth velocity pulse at one end, velocity Verlet with
  // dt = 1e-8 for 600 steps; its README gives the recipe and the conventions matched here
  // (omega = 1 / |xi|, the linear partial volume with lc = a in m, theta and the forces).
  const std::string dir = source_path("reference/lammps/lps_lattice/");
  pd::Model m;
  m.dimension = PdDimension::Solid3D;
  m.spacing = 0.0005;
  m.horizon = 0.0015001;
  m.material_names = {"lammps"};
  const std::vector<double> v0 = test::read_lammps_particles(dir, m, 2200.0);
  REQUIRE(m.particles.size() == 1440);
  const materials::LpsLaw law = materials::lps_law(PdDimension::Solid3D, 25e9, 11538461538.461538);
  m.lps = {law};
  pd::LawTable t;
  t.materials = 1;
  materials::BondLaw bond;
  bond.c = materials::lps_contact_micromodulus(PdDimension::Solid3D, law, m.horizon, 1.0);
  bond.critical_stretch = 1.0;
  bond.alpha = 0.25;
  t.laws = {bond};
  t.law_of = {0};
  pd::build_bonds(m, t, pd::VolumeCorrection::Linear);
  pd::BondState s = pd::initial_state(m, {});
  pd::set_weighted_volumes(m, s);
  m.particles.v = v0;
  const pd::Loading none;
  std::vector<pd::Impactor> no_impactors;
  pd::accelerate(m, s, none, false);
  const std::map<int, std::vector<double>> lammps = test::read_lammps_frames(dir, 1440);
  REQUIRE(lammps.size() == 13);
  double worst = 0.0;
  long broken = 0;
  int compared = 0;
  for (int step = 1; step <= 600; ++step) {
    broken += pd::advance(m, s, none, no_impactors, 1e-8, false).broken;
    const auto it = lammps.find(step);
    if (it == lammps.end()) continue;
    worst = std::max(worst, test::relative_difference(m.particles.u, it->second));
    ++compared;
  }
  std::cout << "lps vs LAMMPS: " << m.bonds.pairs() << " bonds, " << compared
            << " frames, largest difference " << worst
            << " of the largest displacement at that step\n";
  CHECK(compared == 12);
  CHECK(broken == 0);
  CHECK(worst < 1e-8);
}

TEST_CASE("LPS keys: what a state-based body does not take is refused naming the key",
          "[pd][lps][input]") {
  const YAML::Node base = YAML::LoadFile(source_path("problems/pd_disk_impact_lps.yaml"));
  const auto refused = [&](const std::vector<std::string>& overrides, const std::string& start) {
    YAML::Node root = YAML::Clone(base);
    for (const std::string& o : overrides) spec::apply_override(root, o);
    CHECK_THROWS_WITH(spec::parse_problem(root), Catch::StartsWith(start));
  };
  // The problem as shipped reads, with K and G or with E and nu, and any influence function.
  CHECK(spec::parse_problem(YAML::Clone(base)).pd().state_based());
  {
    YAML::Node root = YAML::Clone(base);
    root["materials"][0].remove("bulk_modulus");
    root["materials"][0].remove("shear_modulus");
    spec::apply_override(root, "materials.0.E=30e9");
    spec::apply_override(root, "materials.0.nu=0.3");
    spec::apply_override(root, "materials.0.bond.influence=gaussian");
    const spec::ProblemSpec p = spec::parse_problem(root);
    CHECK(p.pd().materials[0].bond->influence == materials::Influence::Gaussian);
  }
  refused({"materials.0.bond.influence=cubic"}, "materials[0].bond.influence:");
  refused({"materials.0.bond.micromodulus=1e22"}, "materials[0].bond.micromodulus:");
  refused({"materials.0.bond.law=pmb", "materials.0.bond.influence=constant"},
          "materials[0].bond.influence: an influence function belongs to law: lps");
  refused({"materials.0.bond.yield_stretch=0.001"}, "materials[0].bond.yield_stretch:");
  refused({"materials.0.bond.yield_stress=3e8"},
          "materials[0].bond.yield_stress: a yield stress belongs to law: eps");
  refused({"materials.0.bond.law=eps"}, "materials[0].bond.yield_stress:");
  CHECK(spec::parse_problem([&] {
          YAML::Node root = YAML::Clone(base);
          spec::apply_override(root, "materials.0.bond.law=eps");
          spec::apply_override(root, "materials.0.bond.yield_stress=3e8");
          return root;
        }())
            .pd()
            .materials[0]
            .bond->yield_stress == 3e8);
  refused({"materials.0.E=30e9"}, "materials[0].bulk_modulus: give E and nu, or bulk_modulus");
  {
    YAML::Node root = YAML::Clone(base);
    root["materials"][0].remove("shear_modulus");
    CHECK_THROWS_WITH(spec::parse_problem(root),
                      Catch::StartsWith("materials[0].nu: law: lps needs"));
  }
  refused({"discretisation.surface_correction=energy"},
          "discretisation.surface_correction: energy corrects bond-based bodies; an lps body "
          "takes position_aware");
  CHECK(spec::parse_problem([&] {
          YAML::Node root = YAML::Clone(base);
          spec::apply_override(root, "discretisation.surface_correction=position_aware");
          return root;
        }())
            .pd()
            .surface_correction == "position_aware");
  {
    YAML::Node root = YAML::Clone(base);
    root["materials"][0].remove("bulk_modulus");
    root["materials"][0].remove("shear_modulus");
    for (const char* o : {"materials.0.E=30e9", "materials.0.bond.law=pmb",
                          "discretisation.surface_correction=position_aware"})
      spec::apply_override(root, o);
    CHECK_THROWS_WITH(spec::parse_problem(root),
                      Catch::StartsWith("discretisation.surface_correction: position_aware "
                                        "corrects lps bodies; a bond-based body takes energy"));
  }
  refused({"discretisation.surface_correction=position_aware", "materials.0.bond.law=eps",
           "materials.0.bond.yield_stress=3e8"},
          "discretisation.surface_correction: position_aware is elastic; 'lammps' is eps");
  refused({"discretisation.surface_correction=aware"}, "discretisation.surface_correction:");
  {
    // A second material of another family in the same body.
    YAML::Node root = YAML::Clone(base);
    YAML::Node steel = YAML::Load("{name: steel, E: 200e9, density: 7850, bond: {law: pmb}}");
    root["materials"].push_back(steel);
    root["regions"] = YAML::Load("[{box: [[-0.001, -0.001, -0.005], [0.001, 0.001, 0]], material: "
                                 "steel}]");
    root["material"] = "lammps";
    CHECK_THROWS_WITH(spec::parse_problem(root),
                      Catch::StartsWith("materials[1].bond.law: a body's materials are all"));
  }
  {
    // EPS is a 3D model.
    YAML::Node root = YAML::LoadFile(source_path("problems/staged_pmma_impact.yaml"));
    spec::apply_override(root, "materials.0.bond.law=eps");
    spec::apply_override(root, "materials.0.bond.yield_stress=3e7");
    CHECK_THROWS_WITH(spec::parse_problem(root),
                      Catch::StartsWith("materials[0].bond.law: law: eps (Mitchell 2011) is a 3D"));
  }
  {
    // A plane state-based stage after a preload takes Newton-Krylov steps, as a bond-based one
    // takes Newton's, unless ADR is asked for.
    YAML::Node root = YAML::LoadFile(source_path("problems/staged_pmma_impact.yaml"));
    spec::apply_override(root, "materials.0.bond.law=lps");
    CHECK(spec::parse_problem(root).staged().links[1].implicit_equilibrium);
    spec::apply_override(root, "stages.1.transfer.equilibrium=adr");
    CHECK_FALSE(spec::parse_problem(root).staged().links[1].implicit_equilibrium);
  }
}

namespace {

/// An EPS lattice: lps_lattice with a yield stress, its yield values set.
pd::Model eps_lattice(int n, const Elastic& el, double yield, materials::Influence influence,
                      bool deterministic) {
  pd::Model m = lps_lattice(PdDimension::Solid3D, n, n, n, 1e-3, 3.0, el, 7850.0,
                            pd::VolumeCorrection::Exact, influence, deterministic);
  m.lps[0].yield_stress = yield;
  pd::set_weighted_volumes(m, pd::initial_state(m, {}));
  return m;
}

} // namespace

TEST_CASE("EPS under a cyclic deviatoric extension path follows its closed form",
          "[pd][lps][eps]") {
  // The centre's partners moved along their bonds so that every bond of the centre extends by
  // e_j = lambda g_j, g_j = |xi_j| n_j . D n_j with D deviatoric: its dilatation stays zero (the
  // family's moments are cubic), so its deviatoric state is one scalar: the trial force state
  // b omega (lambda - p) g_j and |t^d| = b |lambda - p| G, G^2 = sum_j omega^2 g_j^2 w_j, and the
  // radial return is the elastic-perfectly plastic law of one variable: |lambda - p| <= lambda_Y
  // = sqrt(2 psi0) / (b G). Every bond's plastic extension p g_j and the centre's energy
  // density b (lambda - p)^2 G'^2 / 2 (G'^2 = sum_j omega g_j^2 w_j) to 1e-8, over a path that
  // loads, reverses through yield both ways and unloads.
  const Elastic el{200e9, 0.3};
  const double yield = 250e6;
  using I = materials::Influence;
  for (I influence : {I::Constant, I::InverseLength}) {
    for (const Eigen::Matrix3d& D :
         {Eigen::Matrix3d((Eigen::Matrix3d() << 0, 1, 0, 1, 0, 0, 0, 0, 0).finished()),
          Eigen::Matrix3d((Eigen::Matrix3d() << 1, 0, 0, 0, -0.5, 0.3, 0, 0.3, -0.5).finished())}) {
      pd::Model m = eps_lattice(11, el, yield, influence, true);
      const int centre = centre_of(PdDimension::Solid3D, 11);
      const pd::Bonds& bonds = m.bonds;
      const Eigen::Vector3d xc = m.particles.reference(centre);
      double G2 = 0.0, G2e = 0.0;
      std::vector<double> g;
      for (long k = bonds.offset[centre]; k < bonds.offset[centre + 1]; ++k) {
        const pd::BondClass& c = bonds.classes[bonds.cls[k]];
        const Eigen::Vector3d n = (m.particles.reference(bonds.partner[k]) - xc) / c.length;
        g.push_back(c.length * n.dot(D * n));
        const double om = materials::influence(influence, c.length, m.horizon);
        G2 += om * om * g.back() * g.back() * c.weight;
        G2e += om * g.back() * g.back() * c.weight;
      }
      const double b = 15.0 * el.mu() / m.weighted_volume[centre];
      const double lambda_y = std::sqrt(2.0 * m.yield_value[centre]) / (b * std::sqrt(G2));
      pd::BondState s = pd::initial_state(m, {});
      double p = 0.0, worst_p = 0.0, worst_w = 0.0;
      int yielded = 0;
      const double path[] = {0.5, 1.3, 2.6, 1.2, -0.4, -2.2, -3.1, -1.0, 0.7, 2.9, 0.0};
      for (double at : path) {
        const double lambda = at * lambda_y;
        std::vector<double> y = m.particles.X;
        for (long k = bonds.offset[centre]; k < bonds.offset[centre + 1]; ++k) {
          const int j = bonds.partner[k];
          const pd::BondClass& c = bonds.classes[bonds.cls[k]];
          const Eigen::Vector3d n = (m.particles.reference(j) - xc) / c.length;
          for (int d = 0; d < 3; ++d)
            y[3 * j + d] = xc(d) + (c.length + lambda * g[k - bonds.offset[centre]]) * n(d);
        }
        std::vector<double> f, w;
        pd::state_forces(m, s, y, f, true, &w);
        const double trial = lambda - p;
        if (std::abs(trial) > lambda_y) ++yielded;
        p = lambda - std::clamp(trial, -lambda_y, lambda_y);
        double g_max = 0.0;
        for (double gj : g) g_max = std::max(g_max, std::abs(gj));
        for (long k = bonds.offset[centre]; k < bonds.offset[centre + 1]; ++k)
          worst_p = std::max(worst_p, std::abs(s.plastic[2 * k] - p * g[k - bonds.offset[centre]]) /
                                          (lambda_y * g_max));
        const double w_exact = 0.5 * b * (lambda - p) * (lambda - p) * G2e;
        worst_w = std::max(worst_w,
                           std::abs(w[centre] - w_exact) / (0.5 * b * lambda_y * lambda_y * G2e));
      }
      std::cout << "eps closed form, influence " << static_cast<int>(influence) << ": " << yielded
                << " of 11 states yielding, plastic extension within " << worst_p
                << " of lambda_Y max|g|, energy within " << worst_w << "\n";
      CHECK(yielded >= 5);
      CHECK(worst_p < 1e-8);
      CHECK(worst_w < 1e-8);
    }
  }
}

TEST_CASE("EPS: Newton's static solver refuses an elastic-plastic body, which relaxes by ADR",
          "[pd][lps][eps]") {
  pd::Model m =
      eps_lattice(5, Elastic{200e9, 0.3}, 250e6, materials::Influence::InverseLength, false);
  pd::BondState s = pd::initial_state(m, {});
  CHECK_THROWS_WITH(pd::solve_statics(m, s, pd::Loading{}, pd::RelaxSettings{}),
                    Catch::StartsWith("solve_statics: Newton solves elastic state-based bodies"));
}

TEST_CASE("EPS yields under pure shear at von Mises's shear yield stress", "[pd][lps][eps]") {
  // A homogeneous shear strain gamma at twice the continuum's yield, one evaluation from the
  // virgin state: the centre's return factor gives the shear strain at which it yielded,
  // gamma_Y = gamma (1 - e^dp / e^d) for any bond; the shear stress the discrete body carries
  // there, tau_Y = C44 gamma_Y (C44 from the centre's energy under an elastic shear), against
  // von Mises's sigma_Y / sqrt(3).
  const Elastic el{200e9, 0.3};
  const double yield = 250e6, tau_y = yield / std::sqrt(3.0);
  using I = materials::Influence;
  for (I influence : {I::Constant, I::InverseLength, I::Gaussian}) {
    pd::Model m = eps_lattice(11, el, yield, influence, true);
    const int centre = centre_of(PdDimension::Solid3D, 11);
    const double gamma = 2.0 * tau_y / el.mu();
    pd::BondState s = pd::initial_state(m, {});
    std::vector<double> f;
    pd::state_forces(m, s,
                     deformed(m,
                              [&](const Eigen::Vector3d& x) {
                                return Eigen::Vector3d(0.5 * gamma * x.y(), 0.5 * gamma * x.x(),
                                                       0.0);
                              }),
                     f);
    // The bond of largest deviatoric extension, (1, 1, 0) / sqrt(2).
    const pd::Bonds& bonds = m.bonds;
    double ratio = 0.0;
    for (long k = bonds.offset[centre]; k < bonds.offset[centre + 1]; ++k) {
      const Eigen::Vector3d xi =
          m.particles.reference(bonds.partner[k]) - m.particles.reference(centre);
      if (std::abs(xi.x() - 1e-3) > 1e-9 || std::abs(xi.y() - 1e-3) > 1e-9 ||
          std::abs(xi.z()) > 1e-9)
        continue;
      const double length = xi.norm();
      const double e =
          std::sqrt((xi.x() + 0.5 * gamma * xi.y()) * (xi.x() + 0.5 * gamma * xi.y()) +
                    (xi.y() + 0.5 * gamma * xi.x()) * (xi.y() + 0.5 * gamma * xi.x())) -
          length;
      ratio = 1.0 - s.plastic[2 * k] / e; // theta is second order in gamma: below 1e-6 of e
    }
    Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
    G(0, 1) = 1e-6;
    const double c44 = 2.0 * energy_density(m, centre, G) / (1e-6 * 1e-6);
    const double tau = c44 * gamma * ratio;
    std::cout << "eps shear yield, influence " << static_cast<int>(influence) << ": tau_Y " << tau
              << " against sigma_Y / sqrt(3) " << tau_y << " (ratio " << tau / tau_y << ")\n";
    CHECK(std::abs(tau / tau_y - 1.0) < 0.01);
  }
}

TEST_CASE("EPS: both layouts give the same forces and plastic states along a plastic path",
          "[pd][lps][eps]") {
  const Elastic el{200e9, 0.3};
  std::vector<double> f_half, f_full;
  for (bool full : {false, true}) {
    pd::Model m = eps_lattice(8, el, 250e6, materials::Influence::InverseLength, full);
    pd::BondState s = pd::initial_state(m, {});
    std::vector<double>& f = full ? f_full : f_half;
    for (double a : {0.002, 0.004, 0.001, -0.003}) {
      const std::vector<double> y = deformed(m, [a](const Eigen::Vector3d& x) {
        return Eigen::Vector3d(a * x.y() + 40.0 * a * x.x() * x.x(), a * x.x(), -0.5 * a * x.z());
      });
      pd::state_forces(m, s, y, f);
    }
  }
  double scale = 0.0, diff = 0.0;
  for (std::size_t k = 0; k < f_full.size(); ++k) {
    scale = std::max(scale, std::abs(f_full[k]));
    diff = std::max(diff, std::abs(f_half[k] - f_full[k]));
  }
  std::cout << "eps layouts: half - full " << diff / scale << " of the largest force\n";
  CHECK(diff < 1e-12 * scale);
}
