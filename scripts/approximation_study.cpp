// Function approximation by plain SPH kernel sums and by reproducing-kernel (RK) shape functions,
// the comparison of [Faraji 2007] section 4-1 (its Figs. 4-1 to 4-7): linear, quadratic and cos(x)
// in 1D; z = 2x + y and z = 2x^2 + y^2 in 2D. Writes one CSV per case into the given directory;
// scripts/plot_approximation.py turns them into PNG plots.
//   approximation_study OUTDIR
#include "meshfree/core/error.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/io/output.hpp"
#include <cmath>
#include <functional>
#include <iostream>

using namespace mf;

namespace {

struct Case {
  std::string name;
  int dim;
  std::function<double(const Vec2&)> f;
};

geometry::NodeCloud lattice(int dim, int n) {
  geometry::NodeCloud c;
  const double h = 1.0 / (n - 1);
  for (int j = 0; j < (dim == 1 ? 1 : n); ++j)
    for (int i = 0; i < n; ++i) {
      c.x.emplace_back(i * h, j * h);
      c.spacing.push_back(h);
      c.volume.push_back(dim == 1 ? h : h * h);
    }
  return c;
}

/// Approximation of f at the points from nodal values f(x_I) with the given construction.
std::vector<double> approximate(const implicit::MeshfreeSpace& space, const std::vector<Vec2>& pts,
                                const std::function<double(const Vec2&)>& f) {
  std::vector<int> rows(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) rows[i] = static_cast<int>(i);
  const auto t = space.shape_table(pts, rows, space.support_lists(pts), false);
  std::vector<double> out(pts.size(), 0.0);
  for (int r = 0; r < t.rows(); ++r)
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k)
      out[r] += t.phi[k] * f(space.nodes().x[t.node[k]]);
  return out;
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: approximation_study OUTDIR\n";
    return 2;
  }
  try {
    const std::vector<Case> cases = {
        {"1d_linear", 1, [](const Vec2& x) { return 1.0 + 2.0 * x.x(); }},
        {"1d_quadratic", 1, [](const Vec2& x) { return x.x() * x.x(); }},
        {"1d_cos", 1, [](const Vec2& x) { return std::cos(2.0 * M_PI * x.x()); }},
        {"2d_linear", 2, [](const Vec2& x) { return 2.0 * x.x() + x.y(); }},
        {"2d_quadratic", 2, [](const Vec2& x) { return 2.0 * x.x() * x.x() + x.y() * x.y(); }},
    };
    io::OutputDirectory out(argv[1]);
    for (const auto& c : cases) {
      const int n = c.dim == 1 ? 11 : 11;
      kernels::ShapeSettings s;
      s.dim = c.dim;
      s.window.type = kernels::WindowType::CubicSpline;
      std::vector<Vec2> pts;
      const int m = c.dim == 1 ? 201 : 41;
      for (int j = 0; j < (c.dim == 1 ? 1 : m); ++j)
        for (int i = 0; i < m; ++i)
          pts.emplace_back(i / (m - 1.0), c.dim == 1 ? 0.0 : j / (m - 1.0));
      std::vector<std::vector<double>> columns;
      for (auto [approx, basis] :
           {std::pair{kernels::Approximation::Sph, kernels::Basis::Linear},
            std::pair{kernels::Approximation::ReproducingKernel, kernels::Basis::Linear},
            std::pair{kernels::Approximation::ReproducingKernel, kernels::Basis::Quadratic}}) {
        s.approximation = approx;
        s.basis = basis;
        const double dil = basis == kernels::Basis::Quadratic ? 3.0 : 2.0;
        const implicit::MeshfreeSpace space(lattice(c.dim, n), s, Vec2(dil, dil));
        columns.push_back(approximate(space, pts, c.f));
      }
      std::vector<std::vector<double>> rows;
      for (std::size_t i = 0; i < pts.size(); ++i)
        rows.push_back(
            {pts[i].x(), pts[i].y(), c.f(pts[i]), columns[0][i], columns[1][i], columns[2][i]});
      out.write_csv("approx_" + c.name + ".csv",
                    {"x", "y", "exact", "sph", "rk_linear", "rk_quadratic"}, rows);
    }
    out.commit();
  } catch (const Error& e) {
    std::cerr << "approximation_study: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
