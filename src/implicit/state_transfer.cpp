#include "meshfree/implicit/state_transfer.hpp"
#include "meshfree/implicit/elasticity.hpp"
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
  s.alpha = std::max(v[12], 0.0);
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

/// The nodal averages of the history (weights phi_I(x_g)^2 w_g), on every rank.
std::vector<double> nodal_history(const GalerkinModel& from, const PointStates& st,
                                  const solvers::PetscSession& session) {
  const ShapeTable& t = from.domain_table;
  const int nodes = from.node_count();
  std::vector<double> sum(kValues * static_cast<std::size_t>(nodes) + nodes, 0.0);
  double* weight = sum.data() + kValues * static_cast<std::size_t>(nodes);
  double v[kValues];
  for (int k = 0; k < t.rows(); ++k) {
    if (!from.domain_mine.counted[k]) continue;
    pack(st.committed[k], v);
    const double w = from.domain.weight[from.domain_mine.rows[k]];
    for (int q = t.offset[k]; q < t.offset[k + 1]; ++q) {
      const int I = t.node[q];
      const double c = t.phi[q] * t.phi[q] * w;
      for (int j = 0; j < kValues; ++j) sum[kValues * I + j] += c * v[j];
      weight[I] += c;
    }
  }
  solvers::sum_everywhere(session.comm(), sum.data(), static_cast<int>(sum.size()));
  for (int I = 0; I < nodes; ++I)
    for (int j = 0; j < kValues; ++j)
      sum[kValues * I + j] = weight[I] > 0.0 ? sum[kValues * I + j] / weight[I] : 0.0;
  sum.resize(kValues * static_cast<std::size_t>(nodes));
  return sum;
}

/// Finds the points of one set at the places of another's: their coordinates rounded to a
/// billionth of the body's size, so that a point made by the same arithmetic is found.
class PointIndex {
public:
  explicit PointIndex(const std::vector<Vec2>& x) {
    BoundingBox box{x.empty() ? Vec2::Zero() : x.front(), x.empty() ? Vec2::Zero() : x.front()};
    for (const Vec2& p : x) box.lo = box.lo.cwiseMin(p), box.hi = box.hi.cwiseMax(p);
    quantum_ = std::max(1e-300, 1e-9 * (box.hi - box.lo).norm());
    for (std::size_t i = 0; i < x.size(); ++i) index_.emplace(key(x[i]), static_cast<int>(i));
  }
  /// The point at x, or -1.
  int find(const Vec2& x) const {
    const auto it = index_.find(key(x));
    return it == index_.end() ? -1 : it->second;
  }

private:
  std::pair<long long, long long> key(const Vec2& x) const {
    return {std::llround(x.x() / quantum_), std::llround(x.y() / quantum_)};
  }
  double quantum_ = 1.0;
  std::map<std::pair<long long, long long>, int> index_;
};

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
  std::vector<double> p = target, gap(target.size());
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
    for (std::size_t i = 0; i < p.size(); ++i) p[i] += gap[i];
  }
  return p;
}

} // namespace

CarriedState carry_state(const GalerkinModel& from, const PointStates& st,
                         const std::vector<double>& d, const GalerkinModel& to,
                         const solvers::PetscSession& session) {
  CarriedState c;
  const std::vector<double> old = every_history(from, st, session);
  const std::vector<double> nodal = nodal_history(from, st, session);
  const PointIndex places(from.domain.x);
  const int rows = to.domain_table.rows();
  c.history.resize(rows);
  std::vector<Vec2> between; // the new points at no old point's place
  std::vector<int> between_rows;
  for (int k = 0; k < rows; ++k) {
    const Vec2& x = to.domain.x[to.domain_mine.rows[k]];
    const int r = places.find(x);
    if (r >= 0) {
      c.history[k] = unpack(old.data() + kValues * static_cast<std::size_t>(r));
      c.copied += to.domain_mine.counted[k];
    } else {
      between.push_back(x);
      between_rows.push_back(k);
      c.interpolated += to.domain_mine.counted[k];
    }
  }
  const ShapeTable t = shapes_at(from, between, false);
  for (int i = 0; i < t.rows(); ++i) {
    double v[kValues] = {};
    for (int q = t.offset[i]; q < t.offset[i + 1]; ++q)
      for (int j = 0; j < kValues; ++j) v[j] += t.phi[q] * nodal[kValues * t.node[q] + j];
    c.history[between_rows[i]] = unpack(v);
  }
  c.copied = solvers::sum_everywhere(session.comm(), c.copied);
  c.interpolated = solvers::sum_everywhere(session.comm(), c.interpolated);

  c.d = interpolating_parameters(from, d, to);
  return c;
}

} // namespace mf::implicit
