#include "meshfree/implicit/state_transfer.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/solvers/parallel.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
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

/// The nearest of a set of points to x (the lowest index among equally near ones), found in a
/// grid of buckets about one point a bucket, searched ring by ring.
class NearestPoint {
public:
  explicit NearestPoint(const std::vector<Vec2>& x) : x_(x) {
    lo_ = hi_ = x.empty() ? Vec2::Zero() : x.front();
    for (const Vec2& p : x) lo_ = lo_.cwiseMin(p), hi_ = hi_.cwiseMax(p);
    const Vec2 size = (hi_ - lo_).cwiseMax(1e-300);
    size_ = std::max(std::sqrt(size.x() * size.y() / std::max<std::size_t>(x.size(), 1)),
                     1e-9 * size.maxCoeff());
    nx_ = static_cast<int>(size.x() / size_) + 1;
    ny_ = static_cast<int>(size.y() / size_) + 1;
    first_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (const Vec2& p : x) ++first_[bucket(p) + 1];
    for (std::size_t b = 1; b < first_.size(); ++b) first_[b] += first_[b - 1];
    points_.resize(x.size());
    std::vector<int> fill(first_.begin(), first_.end() - 1);
    for (std::size_t i = 0; i < x.size(); ++i) points_[fill[bucket(x[i])]++] = static_cast<int>(i);
  }

  int find(const Vec2& p) const {
    const int ci = std::clamp(static_cast<int>((p.x() - lo_.x()) / size_), 0, nx_ - 1);
    const int cj = std::clamp(static_cast<int>((p.y() - lo_.y()) / size_), 0, ny_ - 1);
    int best = -1;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= std::max(nx_, ny_); ++ring) {
      // Every point outside the rings searched is at least `ring` buckets' widths away.
      const double reach = (ring - 1) * size_;
      if (best >= 0 && reach > 0.0 && reach * reach > best_d2) break;
      for (int j = cj - ring; j <= cj + ring; ++j)
        for (int i = ci - ring; i <= ci + ring; ++i) {
          if (std::max(std::abs(i - ci), std::abs(j - cj)) != ring) continue;
          if (i < 0 || j < 0 || i >= nx_ || j >= ny_) continue;
          const std::size_t b = static_cast<std::size_t>(j) * nx_ + i;
          for (int k = first_[b]; k < first_[b + 1]; ++k) {
            const int q = points_[k];
            const double d2 = (x_[q] - p).squaredNorm();
            if (d2 < best_d2 || (d2 == best_d2 && q < best)) best_d2 = d2, best = q;
          }
        }
    }
    return best;
  }

private:
  std::size_t bucket(const Vec2& p) const {
    const int i = std::clamp(static_cast<int>((p.x() - lo_.x()) / size_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((p.y() - lo_.y()) / size_), 0, ny_ - 1);
    return static_cast<std::size_t>(j) * nx_ + i;
  }
  const std::vector<Vec2>& x_;
  Vec2 lo_, hi_;
  double size_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> first_, points_;
};

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

/// The nearest point of the same material (material regions): a history is never carried across
/// an interface.
class NearestInMaterial {
public:
  NearestInMaterial(const spec::ProblemSpec& spec, const std::vector<Vec2>& x) : spec_(spec) {
    for (std::size_t r = 0; r < x.size(); ++r) {
      Points& p = of_[material_at(spec, x[r])];
      p.x.push_back(x[r]);
      p.index.push_back(static_cast<int>(r));
    }
    for (auto& [material, p] : of_) p.search = std::make_unique<NearestPoint>(p.x);
  }
  /// The index of the nearest point of x's material (of any, where none has it).
  int find(const Vec2& x) const {
    auto it = of_.find(material_at(spec_, x));
    if (it == of_.end()) it = of_.begin();
    return it->second.index[it->second.search->find(x)];
  }

private:
  struct Points {
    std::vector<Vec2> x;
    std::vector<int> index;
    std::unique_ptr<NearestPoint> search;
  };
  const spec::ProblemSpec& spec_;
  std::map<int, Points> of_;
};

} // namespace

CarriedState carry_state(const spec::ProblemSpec& spec, const GalerkinModel& from,
                         const PointStates& st, const std::vector<double>& d,
                         const GalerkinModel& to, const solvers::PetscSession& session) {
  CarriedState c;
  const std::vector<double> old = every_history(from, st, session);
  const PointIndex places(from.domain.x);
  const NearestInMaterial nearest(spec, from.domain.x);
  const int rows = to.domain_table.rows();
  c.history.resize(rows);
  for (int k = 0; k < rows; ++k) {
    const Vec2& x = to.domain.x[to.domain_mine.rows[k]];
    int r = places.find(x);
    if (r >= 0) {
      c.copied += to.domain_mine.counted[k];
    } else {
      r = nearest.find(x);
      c.nearest += to.domain_mine.counted[k];
    }
    c.history[k] = unpack(old.data() + kValues * static_cast<std::size_t>(r));
  }
  c.copied = solvers::sum_everywhere(session.comm(), c.copied);
  c.nearest = solvers::sum_everywhere(session.comm(), c.nearest);

  c.d = interpolating_parameters(from, d, to);
  return c;
}

} // namespace mf::implicit
