// Galerkin elasticity against exact solutions: patch test, convergence rates on Timoshenko's
// beam and Kirsch's plate, equilibrium of reactions, and the 1D model problem.
#include "meshfree/implicit/elastic_solve.hpp"
#include "meshfree/implicit/model_problem_1d.hpp"
#include "test_support.hpp"
#include <catch2/catch.hpp>
#include <iostream>

using namespace mf;

namespace {

struct Study {
  std::vector<double> h, l2, energy;
};

Study study(const std::string& problem, const std::vector<double>& spacings,
            const std::vector<std::string>& extra = {}) {
  Study s;
  for (double h : spacings) {
    std::vector<std::string> o = extra;
    o.push_back("discretisation.spacing=" + std::to_string(h));
    const auto r = implicit::solve_elastic_static(load_problem(problem, o), test_session());
    s.h.push_back(h);
    s.l2.push_back(r.error_l2);
    s.energy.push_back(r.error_energy);
    std::cout << problem << " h=" << h << " nodes=" << r.nodes << " e_L2=" << r.error_l2
              << " e_energy=" << r.error_energy << "\n";
  }
  return s;
}

} // namespace

TEST_CASE("patch test: a linear field is reproduced and the error falls with the Gauss order",
          "[elasticity]") {
  std::vector<double> energy;
  for (int order : {2, 4, 6, 8}) {
    const auto r = implicit::solve_elastic_static(
        load_problem("patch_test", {"discretisation.quadrature.order=" + std::to_string(order)}),
        test_session());
    energy.push_back(r.error_energy);
    CHECK(r.error_l2 < 1e-4);
  }
  for (std::size_t i = 1; i < energy.size(); ++i) CHECK(energy[i] < energy[i - 1]);
  CHECK(energy.back() < 5e-6);
}

TEST_CASE("VCI: the linear patch test passes at every Gauss order, which it does not without",
          "[elasticity][vci]") {
  // A stiff penalty (alpha = 1e13 against E = 1): with VCI what is left is the penalty's own
  // error, which falls as 1 / alpha (measured at order 2: energy 2.2e-6, 1.6e-7, 1.8e-9 for
  // alpha = 1e8, 1e10, 1e12), while the quadrature's error without it does not depend on alpha.
  const std::string stiff = "boundary.0.penalty=1e13";
  for (int order : {2, 3}) {
    const std::string o = "discretisation.quadrature.order=" + std::to_string(order);
    const auto plain =
        implicit::solve_elastic_static(load_problem("patch_test", {o, stiff}), test_session());
    const auto vci = implicit::solve_elastic_static(
        load_problem("patch_test", {o, stiff, "discretisation.quadrature.correction=vci"}),
        test_session());
    std::cout << "patch test, Gauss order " << order << ": energy error " << plain.error_energy
              << " without VCI, " << vci.error_energy << " with\n";
    CHECK(plain.error_energy > 1e-6);
    CHECK(vci.error_energy < 1e-9);
    CHECK(vci.error_l2 < 1e-10);
  }
}

TEST_CASE("VCI: Kirsch plate on 2 x 2 Gauss points converges at the linear basis' rates",
          "[elasticity][vci][convergence]") {
  const std::vector<std::string> vci{"discretisation.quadrature.order=2",
                                     "discretisation.quadrature.correction=vci"};
  const Study s = study("plate_hole_kirsch", {0.5, 0.25, 0.125, 0.0625}, vci);
  const double re = convergence_rate(s.h, s.energy), rl = convergence_rate(s.h, s.l2);
  std::cout << "Kirsch with VCI on 2 x 2 points: rates energy " << re << ", L2 " << rl << "\n";
  CHECK(re >= 0.9);
  CHECK(rl >= 1.8);
  CHECK(s.energy.back() < 0.01);
}

/// Linear basis: the energy-norm error must fall at least as h^0.9 and the L2 error as h^1.8
/// (the theory gives h^1 and h^2), and the finest level be below 1% in energy.
void check_linear_basis_rates(const std::string& problem, const std::vector<double>& spacings,
                              const std::vector<std::string>& extra = {}) {
  const Study s = study(problem, spacings, extra);
  const double re = convergence_rate(s.h, s.energy), rl = convergence_rate(s.h, s.l2);
  std::cout << problem << " rates: energy " << re << ", L2 " << rl << "\n";
  CHECK(re >= 0.9);
  CHECK(rl >= 1.8);
  CHECK(s.energy.back() < 0.01);
}

TEST_CASE("Timoshenko beam: energy error falls at least as h^0.9, L2 as h^1.8",
          "[elasticity][convergence]") {
  check_linear_basis_rates("cantilever_timoshenko", {3.0, 1.5, 0.75, 0.375});
}

TEST_CASE("Kirsch plate with a hole: energy error falls at least as h^0.9, L2 as h^1.8",
          "[elasticity][convergence]") {
  check_linear_basis_rates("plate_hole_kirsch", {0.5, 0.25, 0.125, 0.0625});
}

TEST_CASE("Kirsch plate with exact cut cells at the hole: the same rates, the same accuracy",
          "[elasticity][convergence][quadrature]") {
  check_linear_basis_rates("plate_hole_kirsch", {0.5, 0.25, 0.125, 0.0625},
                           {"discretisation.quadrature.cut_cells=arcs"});
}

TEST_CASE("quadratic basis: Timoshenko energy error converges faster than with the linear basis",
          "[elasticity][convergence]") {
  const Study s = study("cantilever_timoshenko", {3.0, 1.5, 0.75},
                        {"discretisation.basis=quadratic", "discretisation.dilation=3.0"});
  const double re = convergence_rate(s.h, s.energy);
  std::cout << "Timoshenko quadratic-basis energy rate " << re << "\n";
  CHECK(re >= 1.8);
}

TEST_CASE("MLS (EFG) shape functions give the same answer as RK on a uniform lattice",
          "[elasticity]") {
  const auto rk =
      implicit::solve_elastic_static(load_problem("cantilever_timoshenko"), test_session());
  const auto mls = implicit::solve_elastic_static(
      load_problem("cantilever_timoshenko", {"discretisation.approximation=mls"}), test_session());
  CHECK(mls.error_energy == Approx(rk.error_energy).epsilon(1e-3));
}

// The balance holds for any solution of K d = f (the shape-function gradients sum to zero, so
// internal forces cancel): this checks the reaction bookkeeping and the solve, not the mechanics,
// which the CalculiX comparison and the exact solutions check.
TEST_CASE("plate in tension: the reaction from the penalty forces balances the applied load",
          "[elasticity]") {
  const auto r = implicit::solve_elastic_static(load_problem("plate_tension"), test_session());
  REQUIRE(r.boundary.size() == 2);
  CHECK(r.boundary[1].force.y() == Approx(1000.0).epsilon(1e-12));
  CHECK(r.boundary[0].force.y() == Approx(-1000.0).epsilon(1e-8));
  CHECK(std::abs(r.boundary[0].force.x()) < 1e-8);
  CHECK(r.violation_relative < 1e-5);
}

TEST_CASE("1D model problem y'' + f = 0: L2 error falls as h^2, H1 as h",
          "[elasticity][convergence]") {
  std::vector<double> h, l2, h1;
  for (double s : {0.1, 0.05, 0.025, 0.0125}) {
    const auto spec = load_problem("ode_1d", {"discretisation.spacing=" + std::to_string(s)});
    const auto r = implicit::solve_model_problem_1d(spec);
    h.push_back(s);
    l2.push_back(r.error_l2);
    h1.push_back(r.error_h1);
  }
  const double rl = convergence_rate(h, l2), rh = convergence_rate(h, h1);
  std::cout << "1D model problem rates: L2 " << rl << ", H1 " << rh << "\n";
  CHECK(rl >= 1.8);
  CHECK(rh >= 0.9);
  CHECK(l2.back() < 1e-4);
}
