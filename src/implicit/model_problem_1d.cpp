#include "meshfree/implicit/model_problem_1d.hpp"
#include "meshfree/core/gauss_legendre.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include <Eigen/LU>
#include <cmath>

namespace mf::implicit {

double model_1d_exact(const spec::ModelProblem1D& p, double x) {
  const double k = p.sine_waves * M_PI / p.length;
  return p.sine_amplitude * std::sin(k * x) + p.linear * x * (p.length * p.length - x * x) / 6.0;
}

double model_1d_exact_slope(const spec::ModelProblem1D& p, double x) {
  const double k = p.sine_waves * M_PI / p.length;
  return p.sine_amplitude * k * std::cos(k * x) +
         p.linear * (p.length * p.length - 3.0 * x * x) / 6.0;
}

double model_1d_source(const spec::ModelProblem1D& p, double x) { // f = -y''
  const double k = p.sine_waves * M_PI / p.length;
  return p.sine_amplitude * k * k * std::sin(k * x) + p.linear * x;
}

namespace {

/// n equally spaced nodes on [0, (n - 1) h].
geometry::NodeCloud line_nodes(int n, double h) {
  geometry::NodeCloud cloud;
  for (int i = 0; i < n; ++i) {
    cloud.x.emplace_back(i * h, 0.0);
    cloud.spacing.push_back(h);
    cloud.volume.push_back(h);
  }
  return cloud;
}

/// Gauss points and weights on the background cells of [0, L].
struct LinePoints {
  std::vector<Vec2> x;
  std::vector<double> w;
};

LinePoints gauss_points(const spec::DiscretisationSpec& disc, double L) {
  LinePoints p;
  const GaussRule& g = gauss_legendre(disc.order);
  const int cells = std::max(1, static_cast<int>(std::ceil(L / disc.cell_size - 1e-9)));
  for (int c = 0; c < cells; ++c)
    for (std::size_t q = 0; q < g.points.size(); ++q) {
      p.x.emplace_back((c + 0.5 * (g.points[q] + 1.0)) * L / cells, 0.0);
      p.w.push_back(0.5 * g.weights[q] * L / cells);
    }
  return p;
}

/// Shape functions and their derivatives at points `x`, one row each.
ShapeTable shape_rows(const MeshfreeSpace& space, const std::vector<Vec2>& x, bool gradients) {
  std::vector<int> rows(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) rows[i] = static_cast<int>(i);
  return space.shape_table(x, rows, space.support_lists(x), gradients);
}

/// K_IJ = int phi_I' phi_J' dx + alpha (phi_I phi_J)|_{0, L};  F_I = int phi_I f dx.
void assemble(const spec::ModelProblem1D& P, const MeshfreeSpace& space, const ShapeTable& t,
              const LinePoints& g, Eigen::MatrixXd& K, Eigen::VectorXd& F) {
  for (int r = 0; r < t.rows(); ++r) {
    const double f = model_1d_source(P, g.x[r].x());
    MF_REQUIRE(std::isfinite(f),
               "problem_1d: the source f = -y'' is not finite at x = ", g.x[r].x(),
               " (sine_amplitude ", P.sine_amplitude, ", sine_waves ", P.sine_waves, ", linear ",
               P.linear, ")");
    for (int a = t.offset[r]; a < t.offset[r + 1]; ++a) {
      F(t.node[a]) += g.w[r] * t.phi[a] * f;
      for (int b = t.offset[r]; b < t.offset[r + 1]; ++b)
        K(t.node[a], t.node[b]) += g.w[r] * t.dphi[a].x() * t.dphi[b].x();
    }
  }
  const std::vector<Vec2> ends{{0.0, 0.0}, {P.length, 0.0}};
  std::vector<int> both{0, 1};
  const ShapeTable e = space.shape_table(ends, both, space.support_lists(ends), false);
  for (int r = 0; r < e.rows(); ++r)
    for (int a = e.offset[r]; a < e.offset[r + 1]; ++a)
      for (int b = e.offset[r]; b < e.offset[r + 1]; ++b)
        K(e.node[a], e.node[b]) += P.penalty * e.phi[a] * e.phi[b];
}

Eigen::VectorXd solve(const Eigen::MatrixXd& K, const Eigen::VectorXd& F) {
  Eigen::VectorXd d = K.partialPivLu().solve(F);
  MF_REQUIRE(d.allFinite() && (K * d - F).norm() <= 1e-8 * F.norm(),
             "the 1D model problem's linear solve failed: relative residual ",
             (K * d - F).norm() / F.norm());
  return d;
}

/// Relative L2 and H1 errors by the Gauss points.
void measure_errors(const spec::ModelProblem1D& P, const ShapeTable& t, const LinePoints& g,
                    const Eigen::VectorXd& d, Model1DResult& R) {
  double s[4] = {0, 0, 0, 0};
  for (int r = 0; r < t.rows(); ++r) {
    double y = 0.0, dy = 0.0;
    for (int a = t.offset[r]; a < t.offset[r + 1]; ++a) {
      y += t.phi[a] * d(t.node[a]);
      dy += t.dphi[a].x() * d(t.node[a]);
    }
    const double ye = model_1d_exact(P, g.x[r].x()), dye = model_1d_exact_slope(P, g.x[r].x());
    s[0] += g.w[r] * (y - ye) * (y - ye);
    s[1] += g.w[r] * ye * ye;
    s[2] += g.w[r] * (dy - dye) * (dy - dye);
    s[3] += g.w[r] * dye * dye;
  }
  for (const double sum : s)
    MF_REQUIRE(std::isfinite(sum),
               "problem_1d: the solution's norms overflow a double "
               "(sine_amplitude ",
               P.sine_amplitude, ", linear ", P.linear, ")");
  R.error_l2 = std::sqrt(s[0] / s[1]);
  R.error_h1 = std::sqrt(s[2] / s[3]);
}

/// The solution and the exact one at 10 samples per node interval, and the relative max error.
void sample_solution(const spec::ModelProblem1D& P, const MeshfreeSpace& space, int n,
                     const Eigen::VectorXd& d, Model1DResult& R) {
  const double L = P.length;
  const int samples = 10 * (n - 1) + 1;
  std::vector<Vec2> sx;
  for (int k = 0; k < samples; ++k) sx.emplace_back(L * k / (samples - 1), 0.0);
  const ShapeTable st = shape_rows(space, sx, true);
  double ymax = 0.0, emax = 0.0;
  for (int r = 0; r < st.rows(); ++r) {
    double y = 0.0, dy = 0.0;
    for (int a = st.offset[r]; a < st.offset[r + 1]; ++a) {
      y += st.phi[a] * d(st.node[a]);
      dy += st.dphi[a].x() * d(st.node[a]);
    }
    R.x.push_back(sx[r].x());
    R.y.push_back(y);
    R.dy.push_back(dy);
    R.y_exact.push_back(model_1d_exact(P, sx[r].x()));
    R.dy_exact.push_back(model_1d_exact_slope(P, sx[r].x()));
    ymax = std::max(ymax, std::abs(R.y_exact.back()));
    emax = std::max(emax, std::abs(y - R.y_exact.back()));
  }
  R.error_max = emax / ymax;
}

} // namespace

Model1DResult solve_model_problem_1d(const spec::ProblemSpec& spec) {
  Model1DResult R;
  const spec::ModelProblem1D& P = spec.model_1d();
  const spec::DiscretisationSpec& disc = P.discretisation;
  const double L = P.length;
  const int n = static_cast<int>(std::round(L / disc.spacing)) + 1;
  MF_REQUIRE(n >= 3 && n <= 4000, "discretisation.spacing: gives ", n, " nodes on [0, ", L,
             "]; the 1D model problem takes 3 to 4000");
  const MeshfreeSpace space(line_nodes(n, L / (n - 1)), disc.shape, disc.dilation);
  R.nodes = n;
  const LinePoints g = gauss_points(disc, L);
  R.points = static_cast<int>(g.x.size());
  const ShapeTable t = shape_rows(space, g.x, true);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd F = Eigen::VectorXd::Zero(n);
  {
    PhaseTimer::Scope scope(R.timer, "assembly");
    assemble(P, space, t, g, K, F);
  }
  Eigen::VectorXd d;
  {
    PhaseTimer::Scope scope(R.timer, "solve");
    d = solve(K, F);
  }
  PhaseTimer::Scope scope(R.timer, "postprocess");
  measure_errors(P, t, g, d, R);
  sample_solution(P, space, n, d, R);
  log::info("1D model problem: ", n, " nodes, relative errors L2 ", R.error_l2, ", H1 ", R.error_h1,
            ", max ", R.error_max);
  return R;
}

} // namespace mf::implicit
