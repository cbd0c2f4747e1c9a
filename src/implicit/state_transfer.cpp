#include "meshfree/implicit/state_transfer.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace mf::implicit {

namespace {

/// The values a point carries: its J2 history (plastic strain, back stress, equivalent plastic
/// strain) and its strain [xx, yy, xy] on its own cloud.
constexpr int kValues = 16;

void pack(const materials::MaterialState& s, const Vec3& strain, double* v) {
  for (int c = 0; c < 6; ++c) v[c] = s.plastic_strain(c), v[6 + c] = s.back_stress(c);
  v[12] = s.alpha;
  for (int c = 0; c < 3; ++c) v[13 + c] = strain(c);
}

materials::MaterialState unpack(const double* v) {
  materials::MaterialState s;
  for (int c = 0; c < 6; ++c) s.plastic_strain(c) = v[c], s.back_stress(c) = v[6 + c];
  s.alpha = v[12];
  return s;
}

Vec3 unpack_strain(const double* v) {
  return {v[13], v[14], v[15]};
}

/// What every point of `from` carries, on every rank (each point counted by one rank).
std::vector<double> every_history(const GalerkinModel& from, const PointStates& st,
                                  const std::vector<double>& d,
                                  const solvers::PetscSession& session) {
  std::vector<double> all(kValues * from.domain.x.size(), 0.0);
  for (int k = 0; k < from.domain_table.rows(); ++k)
    if (from.domain_mine.counted[k])
      pack(st.committed[k], strain_at(from.domain_table, k, d),
           all.data() + kValues * from.domain_mine.rows[k]);
  solvers::sum_everywhere(session.comm(), all.data(), static_cast<int>(all.size()));
  return all;
}

/// The gradient of u^h at table row r (row c: the gradient of component c).
Mat2 gradient_at(const ShapeTable& t, int r, const std::vector<double>& d) {
  Mat2 g = Mat2::Zero();
  for (int q = t.offset[r]; q < t.offset[r + 1]; ++q)
    g += Vec2(d[2 * t.node[q]], d[2 * t.node[q] + 1]) * t.dphi[q].transpose();
  return g;
}

/// Nodal parameters of `to` whose u^h is the projection of u^h of `from` (parameters d) in the
/// norm |grad v|^2 + |v|^2 / l^2 integrated over the body on the integration points of `to`, l
/// the mean node spacing. One scalar system for both components (each component's gradient is
/// fitted alike), solved by sparse Cholesky. Its strain follows the old strain where the clouds
/// differ: the fit of u^h at the new nodes alone (RK shape functions do not interpolate) solves a
/// system whose rows mix supports of two spacings where boxes meet, and its u^h, exact at the
/// nodes, wiggles between them (README: refinement during the analysis).
std::vector<double> projected_parameters(const GalerkinModel& from, const std::vector<double>& d,
                                         const GalerkinModel& to) {
  // Every point of the body, not this rank's rows, so that every rank solves the same system.
  const std::vector<double>& w = to.domain.weight;
  const ShapeTable t = shapes_at(to, to.domain.x, true);
  const ShapeTable old_at = shapes_at(from, to.domain.x, true);
  std::vector<Vec2> old_u(t.rows());
  std::vector<Mat2> old_grad(t.rows());
  for (int k = 0; k < t.rows(); ++k)
    old_u[k] = displacement_at(old_at, k, d), old_grad[k] = gradient_at(old_at, k, d);
  const int n = to.node_count();
  const double inverse_l2 = n / std::accumulate(w.begin(), w.end(), 0.0);
  // Each row I summed in turn over the entries q of the points whose support holds I.
  std::vector<std::vector<std::pair<int, int>>> entries_of(n); // (point, entry)
  for (int k = 0; k < t.rows(); ++k)
    for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) entries_of[t.node[q]].emplace_back(k, q);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
  std::vector<double> sum(n, 0.0);
  std::vector<char> touched(n, 0);
  std::vector<int> columns;
  for (int I = 0; I < n; ++I) {
    for (const auto& [k, qI] : entries_of[I]) {
      for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) {
        const int J = t.node[q];
        if (!touched[J]) touched[J] = 1, columns.push_back(J);
        sum[J] += w[k] * (t.dphi[qI].dot(t.dphi[q]) + inverse_l2 * t.phi[qI] * t.phi[q]);
      }
      rhs.row(I) +=
          w[k] * (old_grad[k] * t.dphi[qI] + inverse_l2 * t.phi[qI] * old_u[k]).transpose();
    }
    for (int J : columns) entries.emplace_back(I, J, sum[J]), sum[J] = 0.0, touched[J] = 0;
    columns.clear();
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  MF_REQUIRE(ldlt.info() == Eigen::Success,
             "state transfer: the new cloud's projection system is singular");
  const Eigen::MatrixX2d p = ldlt.solve(rhs);
  std::vector<double> out(2 * static_cast<std::size_t>(n));
  for (int I = 0; I < n; ++I) out[2 * I] = p(I, 0), out[2 * I + 1] = p(I, 1);
  return out;
}

/// The nearest old point of a point's own material (material regions: a history is never
/// carried across an interface), the lowest index among equally near ones; each material's
/// points in a cell list (neighbors::PointGrid) searched in growing circles.
class NearestInMaterial {
public:
  NearestInMaterial(const spec::ProblemSpec& spec, const std::vector<Vec2>& x)
      : spec_(spec), x_(x) {
    BoundingBox box{x.front(), x.front()};
    for (const Vec2& p : x) box.lo = box.lo.cwiseMin(p), box.hi = box.hi.cwiseMax(p);
    const Vec2 size = box.hi - box.lo;
    place_ = 1e-9 * size.norm();
    reach_ = std::max(std::sqrt(size.x() * size.y() / static_cast<double>(x.size())), place_);
    std::map<int, std::vector<Vec2>> points;
    for (std::size_t r = 0; r < x.size(); ++r) {
      const int m = material_at(spec, x[r]);
      points[m].push_back(x[r]);
      index_[m].push_back(static_cast<int>(r));
    }
    for (auto& [m, p] : points) grid_.emplace(m, neighbors::PointGrid(p, reach_));
  }

  /// The old point nearest to x of x's material (of the first material, where none has it).
  int find(const Vec2& x) const {
    auto grid = grid_.find(material_at(spec_, x));
    if (grid == grid_.end()) grid = grid_.begin();
    const std::vector<int>& index = index_.at(grid->first);
    int best = -1;
    double best_d2 = 0.0;
    for (double r = reach_; best < 0; r *= 2.0) // every point within r is visited
      grid->second.for_each_within(x, r, [&](int i) {
        const int q = index[i];
        const double d2 = (x_[q] - x).squaredNorm();
        if (best < 0 || d2 < best_d2 || (d2 == best_d2 && q < best)) best = q, best_d2 = d2;
      });
    return best;
  }
  /// Whether the old point r lies at x (a point made by the same arithmetic as an old one).
  bool at_place(int r, const Vec2& x) const { return (x_[r] - x).norm() <= place_; }

private:
  const spec::ProblemSpec& spec_;
  const std::vector<Vec2>& x_;
  double place_ = 0.0, reach_ = 1.0; // a billionth of the body's size; the mean spacing
  std::map<int, neighbors::PointGrid> grid_;
  std::map<int, std::vector<int>> index_; // a grid's points as indices of x
};

} // namespace

CarriedState carry_state(const spec::ProblemSpec& spec, const GalerkinModel& from,
                         const PointStates& st, const std::vector<double>& d,
                         const GalerkinModel& to, const solvers::PetscSession& session) {
  CarriedState c;
  c.d = projected_parameters(from, d, to);
  const std::vector<double> old = every_history(from, st, d, session);
  const NearestInMaterial nearest(spec, from.domain.x);
  const int rows = to.domain_table.rows();
  c.history.resize(rows);
  c.old_strain.resize(rows);
  for (int k = 0; k < rows; ++k) {
    const Vec2& x = to.domain.x[to.domain_mine.rows[k]];
    const int r = nearest.find(x);
    (nearest.at_place(r, x) ? c.copied : c.nearest) += to.domain_mine.counted[k];
    const double* v = old.data() + kValues * static_cast<std::size_t>(r);
    c.history[k] = unpack(v);
    c.old_strain[k] = unpack_strain(v);
  }
  c.copied = solvers::sum_everywhere(session.comm(), c.copied);
  c.nearest = solvers::sum_everywhere(session.comm(), c.nearest);
  return c;
}

std::vector<materials::MaterialState> history_keeping_stress(const CarriedState& c,
                                                             const GalerkinModel& to,
                                                             const std::vector<double>& d) {
  std::vector<materials::MaterialState> h = c.history;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (h[k].alpha <= 0.0) continue; // never yielded: its stress is that of the new strain
    const Vec3 shift = strain_at(to.domain_table, static_cast<int>(k), d) - c.old_strain[k];
    for (int a = 0; a < 3; ++a) h[k].plastic_strain(materials::kPlane[a]) += shift(a);
  }
  return h;
}

} // namespace mf::implicit
