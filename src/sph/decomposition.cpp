#include "meshfree/sph/decomposition.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/sph/symmetry.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace mf::sph {

namespace {

/// Calls visit(info, array) for every per-particle array of the run: the particle set's
/// registry, then SPH's.
template <class Visit> void for_each_field(Hydro& s, Visit&& visit) {
  s.particles.for_each_field(visit);
  s.fields.for_each_field(visit);
}

/// Bytes of one particle's record: the values of every array that migrates.
std::size_t record_bytes(Hydro& s) {
  std::size_t bytes = 0;
  for_each_field(s, [&bytes](const particles::FieldInfo& f, auto& a) {
    if (f.has(particles::kMigrates)) bytes += f.components * sizeof(a[0]);
  });
  return bytes;
}

/// Appends the records of particles `which` to `out`, array by array.
void pack(Hydro& s, const std::vector<int>& which, std::vector<unsigned char>& out) {
  for_each_field(s, [&](const particles::FieldInfo& f, auto& a) {
    if (!f.has(particles::kMigrates)) return;
    const std::size_t per = f.components, item = per * sizeof(a[0]);
    const std::size_t at = out.size();
    out.resize(at + which.size() * item);
    for (std::size_t k = 0; k < which.size(); ++k)
      std::memcpy(&out[at + k * item], &a[per * static_cast<std::size_t>(which[k])], item);
  });
}

/// Appends `count` particles from records that pack() wrote at `in` (an array that does not
/// migrate gets zeros); returns the bytes read.
std::size_t unpack(Hydro& s, const unsigned char* in, std::size_t count) {
  std::size_t at = 0;
  for_each_field(s, [&](const particles::FieldInfo& f, auto& a) {
    const std::size_t per = f.components, item = per * sizeof(a[0]), old = a.size();
    a.resize(old + per * count);
    if (!f.has(particles::kMigrates)) return;
    std::memcpy(&a[old], in + at, count * item);
    at += count * item;
  });
  return at;
}

/// Keeps particles `which` (owned, no ghost present), in that order.
void keep_only(Hydro& s, const std::vector<int>& which) {
  for_each_field(s, [&which](const particles::FieldInfo& f, auto& a) {
    const std::size_t per = f.components;
    std::remove_reference_t<decltype(a)> kept(which.size() * per);
    for (std::size_t k = 0; k < which.size(); ++k)
      for (std::size_t c = 0; c < per; ++c)
        kept[per * k + c] = a[per * static_cast<std::size_t>(which[k]) + c];
    a.swap(kept);
  });
}

/// Drops every ghost, remote ones and mirror images.
void drop_ghosts(Hydro& s) {
  s.particles.drop_ghosts();
  s.fields.truncate(s.particles.size());
  s.remote = 0;
  s.halo = distribution::Halo();
  s.ghost_source.clear();
  s.ghost_planes.clear();
  s.neighbours.x_at_build.clear(); // the list no longer matches the particles
  s.groups.built_for = -1;
}

/// The rank of each owned particle's slab. `replicated`: every rank holds the whole body, and
/// computes the same split without a message.
std::vector<int> slab_owners(const Hydro& s, bool replicated) {
  const particles::ParticleSet& P = s.particles;
  const distribution::Ranks& ranks = s.ranks;
  const int n = P.owned_count();
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = std::numeric_limits<double>::infinity(), hi[d] = -lo[d];
  for (int i = 0; i < n; ++i) {
    const Vec3 x = P.position(i);
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], x[d]), hi[d] = std::max(hi[d], x[d]);
  }
  if (!replicated)
    for (int d = 0; d < 3; ++d) lo[d] = ranks.min(lo[d]), hi[d] = ranks.max(hi[d]);
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
  // Counts are whole numbers, exact in doubles, so the sum over ranks does not depend on order.
  constexpr int bins = 4096;
  const double extent = hi[axis] - lo[axis];
  const auto bin_of = [&](int i) {
    if (!(extent > 0.0)) return 0;
    const int b = static_cast<int>((P.position(i)[axis] - lo[axis]) / extent * bins);
    return std::clamp(b, 0, bins - 1);
  };
  std::vector<double> count(bins, 0.0);
  for (int i = 0; i < n; ++i) count[bin_of(i)] += 1.0;
  if (!replicated) ranks.sum(count.data(), bins);
  const double total = std::accumulate(count.begin(), count.end(), 0.0);
  // A bin goes to the rank whose share of the count holds the bin's middle particle.
  std::vector<int> owner_of_bin(bins);
  double before = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double middle = before + 0.5 * count[b];
    owner_of_bin[b] = std::min(ranks.size - 1, static_cast<int>(middle * ranks.size / total));
    before += count[b];
  }
  std::vector<int> owner(n);
  for (int i = 0; i < n; ++i) owner[i] = owner_of_bin[bin_of(i)];
  return owner;
}

/// Sends the records of particles to[r] to rank r and appends what the other ranks send, rank
/// by rank; returns the number appended from each rank. Collective.
std::vector<int> send_records(Hydro& s, const std::vector<std::vector<int>>& to) {
  const distribution::Ranks& ranks = s.ranks;
  const int R = ranks.size;
  const std::size_t item = record_bytes(s);
  std::vector<unsigned char> out;
  std::vector<int> send_count(R, 0), recv_count(R, 0), send_at(R + 1, 0), recv_at(R + 1, 0);
  for (int r = 0; r < R; ++r) {
    pack(s, to[r], out);
    send_count[r] = static_cast<int>(to[r].size());
  }
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, ranks.comm);
  // Byte counts and offsets; a record set above 2 GiB per message is refused rather than cut.
  std::vector<int> send_bytes(R), recv_bytes(R);
  for (int r = 0; r < R; ++r) {
    MF_REQUIRE(static_cast<double>(std::max(send_count[r], recv_count[r])) * item <
                   std::numeric_limits<int>::max(),
               "SPH: more than 2 GiB of particles to send to one rank; use more ranks");
    send_bytes[r] = static_cast<int>(send_count[r] * item);
    recv_bytes[r] = static_cast<int>(recv_count[r] * item);
    send_at[r + 1] = send_at[r] + send_bytes[r];
    recv_at[r + 1] = recv_at[r] + recv_bytes[r];
  }
  std::vector<unsigned char> in(static_cast<std::size_t>(recv_at[R]));
  MPI_Alltoallv(out.data(), send_bytes.data(), send_at.data(), MPI_BYTE, in.data(),
                recv_bytes.data(), recv_at.data(), MPI_BYTE, ranks.comm);
  for (int r = 0; r < R; ++r)
    if (recv_count[r] > 0) unpack(s, in.data() + recv_at[r], recv_count[r]);
  return recv_count;
}

/// Puts the owned particles (no ghost present) in increasing global id.
void sort_by_id(Hydro& s) {
  const std::vector<long>& id = s.particles.id;
  if (std::is_sorted(id.begin(), id.end())) return;
  std::vector<int> order(id.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&id](int a, int b) { return id[a] < id[b]; });
  keep_only(s, order);
}

} // namespace

void distribute(Hydro& s, const distribution::Ranks& ranks) {
  s.ranks = ranks;
  s.particles_total = s.particles.owned_count();
  if (ranks.serial()) return;
  // A body whose state was set whole (a staged run's transfer) may have its mirror images and
  // lists already: they are made again from each rank's slab at its first build.
  drop_ghosts(s);
  const std::vector<int> owner = slab_owners(s, true);
  std::vector<int> mine;
  for (int i = 0; i < static_cast<int>(owner.size()); ++i)
    if (owner[i] == ranks.rank) mine.push_back(i);
  keep_only(s, mine);
  s.conditions.keep_whole(s.particles);
  s.groups.built_for = -1;
}

void migrate(Hydro& s) {
  if (s.ranks.serial()) return;
  drop_ghosts(s);
  const std::vector<int> owner = slab_owners(s, false);
  std::vector<std::vector<int>> to(s.ranks.size);
  std::vector<int> stay;
  for (int i = 0; i < static_cast<int>(owner.size()); ++i)
    (owner[i] == s.ranks.rank ? stay : to[owner[i]]).push_back(i);
  s.migrated += static_cast<long>(owner.size() - stay.size());
  // The arrivals are appended after every particle held now; then the leavers are dropped.
  const std::size_t before = static_cast<std::size_t>(s.particles.size());
  send_records(s, to);
  std::vector<int> kept = stay;
  for (std::size_t i = before; i < static_cast<std::size_t>(s.particles.size()); ++i)
    kept.push_back(static_cast<int>(i));
  keep_only(s, kept);
  sort_by_id(s);
  s.conditions.cut(s.particles);
  s.groups.built_for = -1;
}

void resume_distribution(Hydro& s) {
  if (s.ranks.serial()) return;
  s.conditions.cut(s.particles);
  const particles::ParticleSet& P = s.particles;
  const long n = P.owned_count();
  MF_REQUIRE(static_cast<std::size_t>(s.remote) == s.remote_owner.size(),
             "SPH: a checkpoint's remote ghosts and their owners do not match");
  const std::vector<long> owned_ids(P.id.begin(), P.id.begin() + n);
  const std::vector<long> ghost_ids(P.id.begin() + n, P.id.begin() + n + s.remote);
  s.halo = distribution::Halo(s.ranks, owned_ids, ghost_ids, s.remote_owner);
}

void fetch_remote_ghosts(Hydro& s, double reach) {
  drop_ghosts(s);
  if (s.ranks.serial()) return;
  const particles::ParticleSet& P = s.particles;
  const distribution::Ranks& ranks = s.ranks;
  const int n = P.owned_count(), R = ranks.size;
  // Every rank's bounding box of its owned particles (an empty rank's is inverted).
  double box[6];
  for (int d = 0; d < 3; ++d)
    box[d] = std::numeric_limits<double>::infinity(), box[3 + d] = -box[d];
  for (int i = 0; i < n; ++i) {
    const Vec3 x = P.position(i);
    for (int d = 0; d < 3; ++d)
      box[d] = std::min(box[d], x[d]), box[3 + d] = std::max(box[3 + d], x[d]);
  }
  std::vector<double> boxes(6 * static_cast<std::size_t>(R));
  MPI_Allgather(box, 6, MPI_DOUBLE, boxes.data(), 6, MPI_DOUBLE, ranks.comm);
  std::vector<std::vector<int>> to(R);
  for (int r = 0; r < R; ++r) {
    const double* b = &boxes[6 * static_cast<std::size_t>(r)];
    if (r == ranks.rank || b[0] > b[3]) continue;
    for (int i = 0; i < n; ++i) {
      const Vec3 x = P.position(i);
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        const double out = std::max({b[d] - x[d], 0.0, x[d] - b[3 + d]});
        d2 += out * out;
      }
      if (d2 <= reach * reach) to[r].push_back(i);
    }
  }
  s.particles.begin_ghosts();
  const std::vector<int> from = send_records(s, to);
  std::vector<long> owned_ids(P.id.begin(), P.id.begin() + n),
      ghost_ids(P.id.begin() + n, P.id.end());
  std::vector<int> ghost_owner;
  for (int r = 0; r < R; ++r) ghost_owner.insert(ghost_owner.end(), from[r], r);
  s.remote = static_cast<int>(ghost_ids.size());
  s.halo = distribution::Halo(ranks, owned_ids, ghost_ids, ghost_owner);
  s.remote_owner = std::move(ghost_owner);
  s.groups.built_for = -1;
}

void refresh_ghosts(Hydro& s) {
  if (!s.ranks.serial()) {
    particles::ParticleSet& P = s.particles;
    ParticleFields& F = s.fields;
    const distribution::Halo& halo = s.halo;
    halo.exchange(P.u, 3), halo.exchange(P.v, 3);
    halo.exchange(F.rho), halo.exchange(F.e), halo.exchange(F.light_time);
    halo.exchange(F.S, 6), halo.exchange(F.alpha), halo.exchange(F.rho_max);
    halo.exchange(F.damage), halo.exchange(F.strain_rate), halo.exchange(F.failed);
  }
  refresh_mirrors(s);
}

void exchange_remote(const Hydro& s, std::vector<double>& a, int per) {
  s.halo.exchange(a, per);
}

void sort_rows_by_id(Hydro& s) {
  const particles::ParticleSet& P = s.particles;
  const int first_mirror = P.owned_count() + s.remote, rows = P.owned_count(), all = P.size();
  // The key (mirror planes, id) of every particle in one integer (ids stay below 2^48), once.
  std::vector<unsigned long> key(all);
#pragma omp parallel for schedule(static)
  for (int j = 0; j < all; ++j) {
    const unsigned long planes = j < first_mirror ? 0UL : s.ghost_planes[j - first_mirror];
    key[j] = planes << 48 | static_cast<unsigned long>(P.id[j]);
  }
  neighbors::PairList& L = s.neighbours.pairs;
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < rows; ++i)
    std::sort(L.partner.begin() + L.offset[i], L.partner.begin() + L.offset[i + 1],
              [&key](int a, int b) { return key[a] < key[b]; });
}

} // namespace mf::sph
