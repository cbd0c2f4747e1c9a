#include "meshfree/geometry/delaunay.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace mf::geometry {

namespace {

/// > 0 when c lies left of the line a -> b.
double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// > 0 when d lies inside the circle through the counter-clockwise a, b, c.
double incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 p = a - d, q = b - d, r = c - d;
  return p.squaredNorm() * (q.x() * r.y() - q.y() * r.x()) -
         q.squaredNorm() * (p.x() * r.y() - p.y() * r.x()) +
         r.squaredNorm() * (p.x() * q.y() - p.y() * q.x());
}

/// A fixed pseudo-random number in [-1, 1] for key k (splitmix64).
double jitter(std::uint64_t k) {
  k += 0x9e3779b97f4a7c15ull;
  k = (k ^ (k >> 30)) * 0xbf58476d1ce4e5b9ull;
  k = (k ^ (k >> 27)) * 0x94d049bb133111ebull;
  k ^= k >> 31;
  return static_cast<double>(k >> 11) * 0x1.0p-52 - 1.0;
}

/// The position of cell (x, y) of a 2^16 x 2^16 grid along the Hilbert curve through it.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) { // the quadrant turned so that the curve enters it where the last one left
      if (rx == 1) x = n - 1 - x, y = n - 1 - y;
      std::swap(x, y);
    }
  }
  return d;
}

/// A triangulation grown by inserting points: counter-clockwise vertices, and for each vertex
/// the neighbour across the edge opposite it (-1 outside).
class Triangulation {
public:
  /// p: the points, the last three those of a triangle around all others.
  explicit Triangulation(std::vector<Vec2> p) : p_(std::move(p)) {
    const int n = static_cast<int>(p_.size());
    v_.push_back({n - 3, n - 2, n - 1});
    nb_.push_back({-1, -1, -1});
    flip_budget_ = 100L * n;
  }

  /// Inserts point i; false when the walk to it or the flips did not end.
  bool insert(int i) {
    const int t = locate(p_[i]);
    if (t < 0) return false;
    split(t, i);
    return legalise();
  }

  const std::vector<Triangle>& vertices() const { return v_; }

private:
  /// A triangle containing x, by a walk from the last one made across an edge x lies beyond
  /// (it ends in a Delaunay triangulation); -1 should it not end.
  int locate(const Vec2& x) const {
    int t = static_cast<int>(v_.size()) - 1;
    for (std::size_t steps = 0; steps < 4 * v_.size() + 16; ++steps) {
      int across = -1;
      for (int e = 0; e < 3 && across < 0; ++e)
        if (orient(p_[v_[t][(e + 1) % 3]], p_[v_[t][(e + 2) % 3]], x) < 0.0) across = e;
      if (across < 0) return t;
      t = nb_[t][across];
    }
    return -1;
  }

  /// Replaces the neighbour `from` of triangle t (if any) by `to`.
  void repoint(int t, int from, int to) {
    if (t < 0) return;
    for (int& n : nb_[t])
      if (n == from) n = to;
  }

  /// Triangle t = (a, b, c) split at its point i into (a, b, i), (b, c, i), (c, a, i); the edges
  /// opposite i queued for legalisation.
  void split(int t, int i) {
    const auto [a, b, c] = v_[t];
    const auto [na, nb, nc] = nb_[t]; // across bc, ca, ab
    const int t1 = static_cast<int>(v_.size()), t2 = t1 + 1;
    v_[t] = {a, b, i};
    nb_[t] = {t1, t2, nc};
    v_.push_back({b, c, i});
    nb_.push_back({t2, t, na});
    v_.push_back({c, a, i});
    nb_.push_back({t, t1, nb});
    repoint(na, t, t1);
    repoint(nb, t, t2);
    queue_ = {t, t1, t2};
  }

  /// Flips the queued edges (each opposite the new point, vertex 2 of its triangle) that are
  /// not locally Delaunay, queueing the two edges each flip exposes.
  bool legalise() {
    while (!queue_.empty()) {
      const int t = queue_.back();
      queue_.pop_back();
      const int u = nb_[t][2];
      if (u < 0) continue;
      int j = 0;
      while (nb_[u][j] != t) ++j;
      const int a = v_[t][0], b = v_[t][1], i = v_[t][2], d = v_[u][j];
      if (incircle(p_[a], p_[b], p_[i], p_[d]) <= 0.0) continue;
      // Only a convex quadrilateral a, d, b, i is flipped (always so in exact arithmetic).
      if (orient(p_[a], p_[d], p_[i]) <= 0.0 || orient(p_[d], p_[b], p_[i]) <= 0.0) continue;
      if (--flip_budget_ < 0) return false;
      const int n_bi = nb_[t][0], n_ia = nb_[t][1];
      const int n_ad = nb_[u][(j + 1) % 3], n_db = nb_[u][(j + 2) % 3];
      v_[t] = {a, d, i};
      nb_[t] = {u, n_ia, n_ad};
      v_[u] = {d, b, i};
      nb_[u] = {n_bi, t, n_db};
      repoint(n_ad, u, t);
      repoint(n_bi, t, u);
      queue_.push_back(t);
      queue_.push_back(u);
    }
    return true;
  }

  std::vector<Vec2> p_;
  std::vector<Triangle> v_, nb_;
  std::vector<int> queue_;
  long flip_budget_ = 0;
};

/// True where the point p of the edge a-b is in the body, or, a and b on a hole's circle, a
/// slot's round end or a re-entrant corner's arc (a chord of it), no nearer its centre than the
/// chord's midpoint.
bool in_body_or_chord(const Domain& domain, const Vec2& a, const Vec2& b, const Vec2& p,
                      double tol) {
  if (domain.contains(p)) return true;
  const auto chord_of = [&](const Vec2& center, double radius) {
    const bool chord = std::abs((a - center).norm() - radius) <= tol &&
                       std::abs((b - center).norm() - radius) <= tol;
    const double midpoint =
        std::sqrt(std::max(0.0, radius * radius - 0.25 * (b - a).squaredNorm()));
    return chord && (p - center).norm() >= midpoint - tol;
  };
  for (const Curve& c : domain.outline()) // a re-entrant arc's chords leave the outline
    if (c.kind == Curve::Kind::Arc && c.theta1 < c.theta0 && chord_of(c.center, c.radius))
      return true;
  if (!domain.within_outline(p)) return false;
  for (const Circle& h : domain.holes())
    if (chord_of(h.center, h.radius)) return true;
  for (const OutlineHole& h : domain.outline_holes())
    for (const Curve& c : h.kind == OutlineHole::Kind::Polygon ? std::vector<Curve>{} : h.loop())
      if (c.kind == Curve::Kind::Arc && chord_of(c.center, c.radius)) return true;
  return false;
}

} // namespace

std::vector<Triangle> delaunay(const std::vector<Vec2>& x) {
  const int n = static_cast<int>(x.size());
  if (n < 3) return {};
  Vec2 lo = x[0], hi = x[0];
  for (const Vec2& p : x) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double size = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<Vec2> p(n + 3);
  for (int i = 0; i < n; ++i)
    p[i] = (x[i] - lo) / size + 1e-9 * Vec2(jitter(2 * i), jitter(2 * i + 1));
  // The outer triangle: far enough that its circles bend little across the points.
  p[n] = Vec2(-50.0, -50.0), p[n + 1] = Vec2(100.0, -50.0), p[n + 2] = Vec2(-50.0, 100.0);
  // Inserted along a Hilbert curve: each point near the last, and no long row whose points
  // would each flip the whole fan of edges above it (rows of a lattice: flips quadratic in the
  // row's length).
  std::vector<std::pair<std::uint64_t, int>> order(n);
  for (int i = 0; i < n; ++i) {
    const Vec2 q = ((x[i] - lo) / size * 65535.0).cwiseMax(0.0).cwiseMin(65535.0);
    order[i] = {hilbert_index(static_cast<std::uint32_t>(q.x()), static_cast<std::uint32_t>(q.y())),
                i};
  }
  std::sort(order.begin(), order.end());
  Triangulation t(std::move(p));
  for (const auto& [key, i] : order)
    if (!t.insert(i)) return {};
  std::vector<Triangle> out;
  const double tiny = 1e-12 * size * size;
  for (const Triangle& v : t.vertices()) {
    if (v[0] >= n || v[1] >= n || v[2] >= n) continue;
    if (orient(x[v[0]], x[v[1]], x[v[2]]) > tiny) out.push_back(v);
  }
  return out;
}

std::vector<Triangle> body_triangles(const Domain& domain, const std::vector<Vec2>& x) {
  std::vector<Triangle> kept;
  const double tol = 1e-9 * domain.bounds().size().maxCoeff();
  for (const Triangle& v : delaunay(x)) {
    const Vec2 centroid = (x[v[0]] + x[v[1]] + x[v[2]]) / 3.0;
    if (!domain.contains(centroid)) continue;
    for (int e = 0; e < 3; ++e) {
      const Vec2 &a = x[v[e]], &b = x[v[(e + 1) % 3]];
      for (double s : {0.25, 0.5, 0.75})
        if (!in_body_or_chord(domain, a, b, a + s * (b - a), tol)) return {};
    }
    kept.push_back(v);
  }
  return kept;
}

} // namespace mf::geometry
