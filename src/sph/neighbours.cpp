#include "meshfree/sph/neighbours.hpp"
#include "meshfree/core/timer.hpp"
#include "meshfree/neighbors/reach_pairs.hpp"
#include "meshfree/sph/decomposition.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

namespace mf::sph {

namespace {
/// The rows of `full` with only the partners j > i: each pair among owned particles once, and
/// every pair with a ghost (ghosts come after the owned particles).
neighbors::PairList later_partners(const neighbors::PairList& full, int owned) {
  neighbors::PairList half;
  half.offset.assign(owned + 1, 0);
  for (int i = 0; i < owned; ++i) {
    long later = 0;
    for (long k = full.offset[i]; k < full.offset[i + 1]; ++k) later += full.partner[k] > i;
    half.offset[i + 1] = half.offset[i] + later;
  }
  half.partner.resize(half.offset[owned]);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < owned; ++i) {
    long at = half.offset[i];
    for (long k = full.offset[i]; k < full.offset[i + 1]; ++k)
      if (full.partner[k] > i) half.partner[at++] = full.partner[k];
  }
  return half;
}
} // namespace

void refresh_neighbours(Hydro& s, bool may_migrate) {
  const auto start = std::chrono::steady_clock::now();
  group_materials(s);
  const particles::ParticleSet& P = s.particles;
  const ParticleFields& F = s.fields;
  const int n = P.size();
  const double skin = s.settings.skin;
  // A pair (i, j) left out at the last build was at least (h_i + h_j)(1 + skin) apart then; it
  // cannot interact yet while every particle has moved and grown its h by less than skin h.
  if (!s.neighbours.x_at_build.empty()) {
    bool stale = false;
#pragma omp parallel for schedule(static) reduction(|| : stale)
    for (int i = 0; i < n; ++i) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double dx = P.X[3 * i + k] + P.u[3 * i + k] - s.neighbours.x_at_build[3 * i + k];
        d2 += dx * dx;
      }
      const double grown = std::max(0.0, F.h[i] - s.neighbours.h_at_build[i]);
      if (std::sqrt(d2) + grown > skin * s.neighbours.h_at_build[i]) stale = true;
    }
    if (!s.ranks.serial()) stale = s.ranks.max(stale ? 1.0 : 0.0) > 0.0;
    if (!stale) {
      s.neighbours.seconds += seconds_since(start);
      return;
    }
  }
  if (may_migrate) migrate(s);
  double h_max = 0.0; // over every rank's owned particles (a rank may hold none)
  for (const int i : P.owned()) h_max = std::max(h_max, F.h[i]);
  h_max = s.ranks.max(h_max);
  s.neighbours.build_radius = 2.0 * h_max * (1.0 + skin);
  if (!s.ranks.serial()) fetch_remote_ghosts(s, s.neighbours.build_radius);
  if (!s.symmetry.empty()) rebuild_mirrors(s, s.neighbours.build_radius);
  group_materials(s);                // when particles came or went
  std::vector<double> x(P.X.size()); // current positions X + u, ghosts included
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = P.X[k] + P.u[k];
  // Pairs within (h_i + h_j)(1 + skin), searched per class of h so that a small particle does
  // not examine every particle within the largest h's reach. Rows for the owned particles, whose
  // rates are computed; ghosts only lend their state, so their rows are empty.
  const int owned = P.owned_count(), with_ghosts = P.size();
  std::vector<double> h(F.h.begin(), F.h.begin() + with_ghosts);
  s.neighbours.pairs = neighbors::pairs_within_reach(x, h, 1.0 + skin, owned);
  s.neighbours.pairs.offset.resize(with_ghosts + 1, s.neighbours.pairs.offset.back());
  if (!s.ranks.serial()) sort_rows_by_id(s);
  if (!s.settings.deterministic)
    s.neighbours.half_pairs = later_partners(s.neighbours.pairs, owned);
  s.neighbours.x_at_build = std::move(x);
  s.neighbours.h_at_build = std::move(h);
  ++s.neighbours.rebuilds;
  s.neighbours.seconds += seconds_since(start);
}

} // namespace mf::sph
