#pragma once
// The numerical parameters of the SPH solver: plain data, held by the problem spec as they are
// (spec/sph_spec.hpp) and by a run (sph::Hydro::settings).
#include "meshfree/kernels/sph_kernel.hpp"

namespace mf::sph {

struct Settings {
  kernels::SphKernel kernel = kernels::SphKernel::CubicSpline;
  double alpha = 1.0, beta = 1.0;    // Monaghan artificial viscosity
  double phi = 0.1;                  // singularity guard of the viscosity, times h
  double courant = 0.3;              // dt = courant * min h / (c + |v|)
  double skin = 0.5;                 // neighbour-list margin: pairs within (h_i + h_j)(1 + skin)
  double burn_width = 2.0;           // programmed burn: the burn fraction rises over this many h
  bool gradient_correction = false;  // kernel-gradient correction (Bonet & Lok 1999)
  double ignition_compression = 0.1; // rho / rho0 - 1 that lights an explosive with an
                                     // unreacted equation of state
  /// Sum every particle's pairs in its row's order (increasing global id), so that the rates do
  /// not depend on the number of threads or ranks; else (the default) each pair is evaluated once
  /// and its terms go to both ends (Newton's third law), the faster (README.md, SPH).
  bool deterministic = false;
  /// Artificial stress against the tensile instability of solids (Monaghan 2000; Gray,
  /// Monaghan & Swift 2001): each particle's tensile principal stresses give
  /// R = -epsilon sigma_tensile / rho^2, and a pair adds f^n (R_i + R_j) to its stress term with
  /// f = W(r) / W(initial spacing). epsilon = 0 switches it off; Gray et al. use 0.3 and n = 4.
  double artificial_stress = 0.0;
  int artificial_stress_exponent = 4;
  /// Inter-material penalty force ([Altafi 2018] eqs. 3-29 and 3-30, after Liu et al. 2003):
  /// particles of different materials closer than r0 = distance x their mean initial spacing
  /// repel with F = pressure a^(dim-1) [(r0/r)^n1 - (r0/r)^n2] along the line of centres,
  /// a = the mean spacing. [Altafi 2018] activates it at (h_i + h_j) / (2 r) >= 1; with
  /// h = 1.5 spacing that would push nearest neighbours apart at rest, so r0 is taken from the
  /// spacing instead. pressure = 0 switches it off.
  struct Penalty {
    double pressure = 0.0;
    int n1 = 12, n2 = 6;
    double distance = 1.0;
  } penalty;
};

} // namespace mf::sph
