#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/core/error.hpp"
#include <array>
#include <cmath>

namespace mf {

namespace {
GaussRule make_rule(int n) {
  GaussRule r;
  r.points.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x; // Bonnet's recursion for P_n and P_n'
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0;
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    r.points[n - 1 - i] = x;
    r.weights[n - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return r;
}
} // namespace

const GaussRule& gauss_legendre(int n) {
  MF_REQUIRE(n >= 1 && n <= 20, "Gauss-Legendre order must be between 1 and 20, got ", n);
  static const std::array<GaussRule, 21> rules = [] {
    std::array<GaussRule, 21> all;
    for (int k = 1; k <= 20; ++k) all[k] = make_rule(k);
    return all;
  }();
  return rules[n];
}

} // namespace mf
