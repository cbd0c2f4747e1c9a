#include "meshfree/implicit/state_transfer.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/neighbors/point_grid.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace mf::implicit {

namespace {

/// The values of a J2 history: plastic strain, back stress, equivalent plastic strain.
constexpr int kValues = 13;

void pack(const materials::J2State& s, double* v) {
  for (int c = 0; c < 6; ++c) v[c] = s.plastic_strain(c), v[6 + c] = s.back_stress(c);
  v[12] = s.alpha;
}

materials::J2State unpack(const double* v) {
  materials::J2State s;
  for (int c = 0; c < 6; ++c) s.plastic_strain(c) = v[c], s.back_stress(c) = v[6 + c];
  s.alpha = v[12];
  return s;
}

/// The history of every point of `from`, on every rank (each point counted by one rank).
std::vector<double> every_history(const GalerkinModel& from, const PointStates& st,
                                  const solvers::PetscSession& session) {
  std::vector<double> all(kValues * from.domain.x.size(), 0.0);
  for (int k = 0; k < from.domain_table.rows(); ++k)
    if (from.domain_mine.counted[k])
      pack(st.committed[k], all.data() + kValues * from.domain_mine.rows[k]);
  solvers::sum_everywhere(session.comm(), all.data(), static_cast<int>(all.size()));
  return all;
}

/// Nodal parameters of `to` whose u^h equals u^h of `from` (parameters d) at the nodes of `to`,
/// found by the fixed-point sweeps d <- d + (u_from(x_I) - u_to(x_I)) from u_from's values; the
/// sweeps stop when they no longer reduce the largest difference (RK shape functions do not
/// interpolate, so the values alone would leave u^h an interpolation error away).
std::vector<double> interpolating_parameters(const GalerkinModel& from,
                                             const std::vector<double>& d,
                                             const GalerkinModel& to) {
  const std::vector<Vec2>& x = to.node_positions();
  const ShapeTable old_at = shapes_at(from, x, false);
  const ShapeTable new_at = shapes_at(to, x, false);
  std::vector<double> target(2 * x.size());
  for (int I = 0; I < old_at.rows(); ++I) {
    const Vec2 u = displacement_at(old_at, I, d);
    target[2 * I] = u.x(), target[2 * I + 1] = u.y();
  }
  std::vector<double> p = target, best = target, gap(target.size());
  double largest = std::numeric_limits<double>::infinity();
  for (int sweep = 0; sweep < 50; ++sweep) {
    double now = 0.0;
    for (int I = 0; I < new_at.rows(); ++I) {
      const Vec2 u = displacement_at(new_at, I, p);
      gap[2 * I] = target[2 * I] - u.x(), gap[2 * I + 1] = target[2 * I + 1] - u.y();
      now = std::max({now, std::abs(gap[2 * I]), std::abs(gap[2 * I + 1])});
    }
    if (!(now < 0.5 * largest)) break;
    largest = now;
    best = p;
    for (std::size_t i = 0; i < p.size(); ++i) p[i] += gap[i];
  }
  return best;
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
  const std::vector<double> old = every_history(from, st, session);
  const NearestInMaterial nearest(spec, from.domain.x);
  const int rows = to.domain_table.rows();
  c.history.resize(rows);
  for (int k = 0; k < rows; ++k) {
    const Vec2& x = to.domain.x[to.domain_mine.rows[k]];
    const int r = nearest.find(x);
    (nearest.at_place(r, x) ? c.copied : c.nearest) += to.domain_mine.counted[k];
    c.history[k] = unpack(old.data() + kValues * static_cast<std::size_t>(r));
  }
  c.copied = solvers::sum_everywhere(session.comm(), c.copied);
  c.nearest = solvers::sum_everywhere(session.comm(), c.nearest);

  c.d = interpolating_parameters(from, d, to);
  return c;
}

} // namespace mf::implicit
