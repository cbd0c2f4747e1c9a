#pragma once
// Gauss-Legendre points and weights on [-1, 1] (Golub & Welsch 1969 give the same nodes; here
// they come from Newton's method on P_n with the asymptotic initial guess).
#include <vector>

namespace mf {

struct GaussRule {
  std::vector<double> points;
  std::vector<double> weights;
};

/// n-point rule, exact for polynomials of degree 2n - 1. n must be in [1, 20].
const GaussRule& gauss_legendre(int n);

} // namespace mf
