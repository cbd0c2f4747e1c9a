// 3 DOFs per node through the solver layer: a box of 8-node hexahedra in linear elasticity,
// assembled by BlockRows (dofs = 3) in place into the matrix's storage, held by penalties on one
// face, loaded on the opposite one and solved by MUMPS, by CG with GAMG (the six rigid-body modes
// as its near-null space) and by Newton (NonlinearBlockSystem). Run on one rank by the unit-test
// suite and on two by ctest `mpi.three_dofs_per_node_two_ranks`.
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "test_support.hpp"
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

using namespace mf;
using namespace mf::implicit;

namespace {

constexpr double kE = 210e9, kNu = 0.3;
constexpr double kPenaltyFactor = 1e6; // alpha = beta E / h per unit area, as in the 2D solver

/// A box of nx x ny x nz cubes of side h from the origin; node (i, j, k) is
/// i + (nx + 1) (j + (ny + 1) k).
struct Box {
  int nx, ny, nz;
  double h;
  int nodes() const { return (nx + 1) * (ny + 1) * (nz + 1); }
  int id(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
  int i(int I) const { return I % (nx + 1); }
  int j(int I) const { return (I / (nx + 1)) % (ny + 1); }
  int k(int I) const { return I / ((nx + 1) * (ny + 1)); }
  Vec3 x(int I) const { return {h * i(I), h * j(I), h * k(I)}; }
  /// The integral of node I's shape function over an end face (x = 0 or x = L): h^2 inside
  /// the face, half on its edges, a quarter at its corners.
  double face_weight(int I) const {
    const auto f = [](int q, int n) { return q == 0 || q == n ? 0.5 : 1.0; };
    return h * h * f(j(I), ny) * f(k(I), nz);
  }
};

/// The cubes' corners, x fastest: numbered so on the box's nodes, they come in increasing order.
std::vector<int> corners(const Box& b, int e) {
  const int ei = e % b.nx, ej = (e / b.nx) % b.ny, ek = e / (b.nx * b.ny);
  std::vector<int> n;
  for (int c = 0; c < 8; ++c) n.push_back(b.id(ei + (c & 1), ej + (c >> 1 & 1), ek + (c >> 2)));
  return n;
}

Csr element_nodes(const Box& b) {
  Csr c;
  for (int e = 0; e < b.nx * b.ny * b.nz; ++e) {
    const std::vector<int> n = corners(b, e);
    c.index.insert(c.index.end(), n.begin(), n.end());
    c.offset.push_back(static_cast<int>(c.index.size()));
  }
  return c;
}

/// The stiffness (24 x 24, row-major, corners as in `corners`) of a cube of side h of trilinear
/// hexahedra in isotropic linear elasticity, K_(a i)(b k) = integral of lambda N_a,i N_b,k +
/// mu (delta_ik grad N_a . grad N_b + N_a,k N_b,i), by 2 x 2 x 2 Gauss points, exact for it
/// [Zienkiewicz, Taylor & Zhu 2013].
std::vector<double> cube_stiffness(double h) {
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  const double g = 1.0 / std::sqrt(3.0), volume_weight = h * h * h / 8.0;
  std::vector<double> K(24 * 24, 0.0);
  for (int q = 0; q < 8; ++q) {
    const double xi[3] = {q & 1 ? g : -g, q >> 1 & 1 ? g : -g, q >> 2 ? g : -g};
    double grad[8][3];
    for (int a = 0; a < 8; ++a) {
      const double s[3] = {a & 1 ? 1.0 : -1.0, a >> 1 & 1 ? 1.0 : -1.0, a >> 2 ? 1.0 : -1.0};
      for (int d = 0; d < 3; ++d) {
        double v = s[d] / 8.0 * (2.0 / h);
        for (int o = 0; o < 3; ++o)
          if (o != d) v *= 1.0 + s[o] * xi[o];
        grad[a][d] = v;
      }
    }
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b) {
        const double dot =
            grad[a][0] * grad[b][0] + grad[a][1] * grad[b][1] + grad[a][2] * grad[b][2];
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k)
            K[(3 * a + i) * 24 + 3 * b + k] +=
                volume_weight * (lambda * grad[a][i] * grad[b][k] +
                                 mu * ((i == k ? dot : 0.0) + grad[a][k] * grad[b][i]));
      }
  }
  return K;
}

/// What holds the box and what loads it.
struct Loading {
  /// true: the face x = 0 held in x, y and z. false: held in x alone, the rigid motions left
  /// (two translations, the rotation about x) held at two corners in y and z where a uniaxial
  /// stress leaves them in place: a bar free to contract.
  bool clamped = true;
  Vec3 traction{0, 0, 0}; // uniform, on the face x = L
  double twist = 0.0;     // a torsional traction on x = L: twist (0, -(z - zc), y - yc)
};

/// Adds the penalty of one node's components `mask` with stiffness `alpha`.
void hold(BlockRows& rows, int node, const bool (&mask)[3], double alpha) {
  double block[9] = {};
  for (int c = 0; c < 3; ++c) block[4 * c] = mask[c] ? alpha : 0.0;
  rows.add_matrix(&node, 1, block);
}

/// The elastic stiffness, the penalties and the loads of the box into `rows` (owned rows only).
void assemble(const Box& b, const Loading& load, BlockRows& rows) {
  const std::vector<double> K = cube_stiffness(b.h);
  const Csr elements = element_nodes(b);
  for (int e = 0; e < elements.rows(); ++e)
    rows.add_matrix(elements.index.data() + elements.offset[e], 8, K.data());
  const double alpha = kPenaltyFactor * kE / b.h; // per unit area of the held face
  const double yc = 0.5 * b.ny * b.h, zc = 0.5 * b.nz * b.h;
  for (int j = 0; j <= b.ny; ++j)
    for (int k = 0; k <= b.nz; ++k) {
      const int held = b.id(0, j, k);
      const bool mask[3] = {true, load.clamped, load.clamped};
      hold(rows, held, mask, alpha * b.face_weight(held));
      const int loaded = b.id(b.nx, j, k);
      const Vec3 x = b.x(loaded);
      const Vec3 t = load.traction + load.twist * Vec3(0.0, -(x.z() - zc), x.y() - yc);
      const Vec3 f = b.face_weight(loaded) * t;
      rows.add_vector(&loaded, 1, f.data());
    }
  if (load.clamped) return;
  const bool yz[3] = {false, true, true}, z[3] = {false, false, true};
  hold(rows, b.id(0, 0, 0), yz, alpha * b.h * b.h);
  hold(rows, b.id(0, b.ny, 0), z, alpha * b.h * b.h);
}

/// The multigrid's settings: CG with GAMG, the x, y, z of the owned nodes for its near-null
/// space.
solvers::LinearSolverSettings multigrid(const Box& b, solvers::OwnedRange own) {
  solvers::LinearSolverSettings s;
  s.multigrid = true;
  for (int I = own.begin; I < own.end; ++I)
    for (int d = 0; d < 3; ++d) s.coordinates.push_back(b.x(I)[d]);
  return s;
}

struct Solved {
  std::vector<double> u; // 3 per node, every node, on every rank
  solvers::SolveReport report;
};

Solved solve(const Box& b, const Loading& load, const solvers::LinearSolverSettings& settings) {
  const solvers::PetscSession& session = test_session();
  const solvers::OwnedRange own = solvers::owned_nodes(b.nodes(), session.rank(), session.size());
  const Csr elements = element_nodes(b);
  const RowPattern p = coupling_pattern({&elements}, b.nodes(), own.begin, own.end);
  solvers::BlockLinearSystem system(
      session.comm(), b.nodes(), own, p.offset, p.column,
      [&](solvers::BlockValueArrays values, std::vector<double>& rhs) {
        BlockRows rows(p, values, 3);
        REQUIRE(rows.dofs() == 3);
        assemble(b, load, rows);
        rhs = rows.rhs();
      },
      /*spd=*/true, settings, /*dofs=*/3);
  Solved s;
  s.report = system.solve();
  s.u = system.solution_everywhere();
  return s;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// The largest difference of u from the uniaxial stress sigma along x, relative to the
/// elongation sigma L / E: u_x = sigma x / E + c, u_y = -nu sigma y / E, u_z = -nu sigma z / E
/// [Timoshenko & Goodier 1970], with c the held face's uniform give under its penalty.
double uniaxial_error(const Box& b, const std::vector<double>& u, double sigma) {
  const double strain = sigma / kE, c = u[0];
  double error = 0.0;
  for (int I = 0; I < b.nodes(); ++I) {
    const Vec3 x = b.x(I);
    const Vec3 exact(strain * x.x() + c, -kNu * strain * x.y(), -kNu * strain * x.z());
    for (int d = 0; d < 3; ++d) error = std::max(error, std::abs(u[3 * I + d] - exact[d]));
  }
  return error / (strain * b.nx * b.h);
}

/// The nodes that the owned rows' elements reach beyond the owned ones.
std::vector<int> needed_nodes(const Csr& elements, solvers::OwnedRange own) {
  std::vector<int> needed;
  for (int e = 0; e < elements.rows(); ++e) {
    const int* n = elements.index.data() + elements.offset[e];
    if (std::none_of(n, n + 8, [&](int I) { return own.owns(I); })) continue;
    for (int a = 0; a < 8; ++a)
      if (!own.owns(n[a])) needed.push_back(n[a]);
  }
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  return needed;
}

/// Newton from zero on the linear residual R(d) = K d - f of the box, with K as its Jacobian:
/// d on every rank.
std::vector<double> newton_solve(const Box& b, const Loading& load, solvers::NewtonReport& r) {
  const solvers::PetscSession& session = test_session();
  const solvers::OwnedRange own = solvers::owned_nodes(b.nodes(), session.rank(), session.size());
  const Csr elements = element_nodes(b);
  const RowPattern p = coupling_pattern({&elements}, b.nodes(), own.begin, own.end);
  BlockRows K(p, 3);
  assemble(b, load, K);
  const auto residual = [&](const std::vector<double>& d, double* R, solvers::ResidualSums& sums) {
    const std::vector<double>& f = K.rhs();
    std::vector<double> internal(f.size(), 0.0);
    K.multiply_add(d, internal.data());
    for (std::size_t q = 0; q < f.size(); ++q) {
      R[q] = internal[q] - f[q];
      sums.scale_squared += internal[q] * internal[q] + f[q] * f[q];
    }
  };
  const auto jacobian = [&](const std::vector<double>&, solvers::BlockValueArrays values) {
    BlockRows(p, values, 3).copy_values(K);
  };
  solvers::NonlinearBlockSystem newton(session.comm(), b.nodes(), own, p.offset, p.column,
                                       needed_nodes(elements, own), residual, jacobian, {},
                                       /*dofs=*/3);
  std::vector<double> d(3 * static_cast<std::size_t>(b.nodes()), 0.0);
  r = newton.solve(d, {});
  std::vector<double> all = newton.gather_on_root(d);
  solvers::broadcast(session.comm(), all, 0);
  return all;
}

} // namespace

// The default relative tolerance of CG, rtol = 1e-12, bounds the error of its answer by
// kappa(BA) rtol relative to the solution, kappa(BA) the condition number of the
// multigrid-preconditioned operator (e = (BA)^-1 B r, [Saad 2003] ch. 9); smoothed aggregation
// keeps kappa(BA) of order 10 for elasticity given its rigid-body modes
// [Vanek, Mandel & Brezina 1996], so the answers must agree to 100 rtol.
constexpr double kMultigridAgreement = 100 * 1e-12;
// CG iterations with the six rigid-body modes as GAMG's near-null space, on one rank or two;
// the translations alone take more than this (README.md, "3 DOFs per node").
constexpr int kMostIterations = 30;

TEST_CASE("3 DOFs per node: a bar of hexahedra in uniaxial tension is exact by MUMPS and by "
          "CG with GAMG",
          "[solvers]") {
  const Box b{12, 3, 3, 0.01};
  const double sigma = 100e6; // F = sigma A
  Loading load;
  load.clamped = false;
  load.traction = {sigma, 0.0, 0.0};
  const Solved direct = solve(b, load, {});
  CHECK(direct.report.solver == "preonly/cholesky/mumps");
  // u(L) - u(0) = F L / (E A), and the contraction nu F / (E A) across the bar.
  CHECK(uniaxial_error(b, direct.u, sigma) < 1e-10);
  const solvers::PetscSession& session = test_session();
  const solvers::OwnedRange own = solvers::owned_nodes(b.nodes(), session.rank(), session.size());
  const Solved iterative = solve(b, load, multigrid(b, own));
  CHECK(iterative.report.solver == "cg/gamg+held-rows");
  CHECK(uniaxial_error(b, iterative.u, sigma) < kMultigridAgreement);
  CHECK(iterative.report.iterations <= kMostIterations);
}

TEST_CASE("3 DOFs per node: a clamped box under tension, bending and torsion: GAMG equals MUMPS "
          "within its tolerance in few iterations",
          "[solvers]") {
  const Box b{16, 6, 6, 0.01}; // 833 nodes, 2499 DOFs
  Loading load;
  load.traction = {20e6, 5e6, -3e6};
  load.twist = 1e9; // Pa per m from the axis: 3e6 Pa at the faces' middles
  const solvers::PetscSession& session = test_session();
  const solvers::OwnedRange own = solvers::owned_nodes(b.nodes(), session.rank(), session.size());
  const Solved direct = solve(b, load, {});
  const Solved iterative = solve(b, load, multigrid(b, own));
  CHECK(iterative.report.solver == "cg/gamg+held-rows");
  std::vector<double> difference(direct.u.size());
  for (std::size_t q = 0; q < difference.size(); ++q) difference[q] = iterative.u[q] - direct.u[q];
  CHECK(max_abs(difference) < kMultigridAgreement * max_abs(direct.u));
  CHECK(iterative.report.iterations <= kMostIterations);
  // Each component moves: the loads reach every rigid mode the face holds.
  for (int d = 0; d < 3; ++d)
    CHECK(std::abs(direct.u[3 * b.id(b.nx, b.ny, b.nz) + d]) > 1e-3 * max_abs(direct.u));
}

TEST_CASE("3 DOFs per node: the multigrid refuses coordinates that are not x, y, z per node",
          "[solvers]") {
  const Box b{4, 2, 2, 0.01};
  const solvers::PetscSession& session = test_session();
  const solvers::OwnedRange own = solvers::owned_nodes(b.nodes(), session.rank(), session.size());
  solvers::LinearSolverSettings s = multigrid(b, own);
  s.coordinates.resize(2 * static_cast<std::size_t>(own.end - own.begin)); // x and y of 2D
  Loading load;
  load.traction = {1e6, 0.0, 0.0};
  REQUIRE_THROWS_WITH(solve(b, load, s),
                      Catch::Contains("multigrid: 3 coordinates per owned node are needed"));
  const RowPattern p = coupling_pattern({}, 4, 0, 4);
  REQUIRE_THROWS_WITH(BlockRows(p, 4), Catch::Contains("BlockRows: 4 DOFs per node"));
}

TEST_CASE("3 DOFs per node: Newton on a clamped box's linear residual takes one iteration to "
          "MUMPS's answer",
          "[solvers]") {
  const Box b{10, 4, 4, 0.01};
  Loading load;
  load.traction = {20e6, 5e6, -3e6};
  load.twist = 1e9;
  solvers::NewtonReport report;
  const std::vector<double> d = newton_solve(b, load, report);
  CHECK(report.converged);
  CHECK(report.iterations == 1);
  const Solved direct = solve(b, load, {});
  REQUIRE(d.size() == direct.u.size());
  std::vector<double> difference(d.size());
  for (std::size_t q = 0; q < d.size(); ++q) difference[q] = d[q] - direct.u[q];
  // The same system factorised by MUMPS alike: the answers differ by round-off.
  CHECK(max_abs(difference) < 1e-12 * max_abs(direct.u));
}
