#include "meshfree/distribution/halo.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cstring>

namespace mf::distribution {

Halo::Halo(const Ranks& ranks, const std::vector<long>& owned_ids,
           const std::vector<long>& ghost_ids, const std::vector<int>& ghost_owner)
    : ranks_(ranks), owned_(static_cast<int>(owned_ids.size())),
      ghosts_(static_cast<int>(ghost_ids.size())) {
  MF_REQUIRE(ghost_ids.size() == ghost_owner.size(), "halo: one owner per ghost");
  MF_REQUIRE(std::is_sorted(ghost_owner.begin(), ghost_owner.end()),
             "halo: ghosts must be grouped by owner rank");
  const int P = ranks.size;
  // What this rank asks of each owner, and what each rank asks of it.
  std::vector<int> want(P, 0), asked(P, 0);
  for (int o : ghost_owner) {
    MF_REQUIRE(o >= 0 && o < P && o != ranks.rank, "halo: a ghost's owner must be another rank");
    ++want[o];
  }
  MPI_Alltoall(want.data(), 1, MPI_INT, asked.data(), 1, MPI_INT, ranks.comm);
  std::vector<int> want_at(P + 1, 0), asked_at(P + 1, 0);
  for (int r = 0; r < P; ++r) {
    want_at[r + 1] = want_at[r] + want[r];
    asked_at[r + 1] = asked_at[r] + asked[r];
  }
  std::vector<long> requested(asked_at[P]);
  MPI_Alltoallv(ghost_ids.data(), want.data(), want_at.data(), MPI_LONG, requested.data(),
                asked.data(), asked_at.data(), MPI_LONG, ranks.comm);
  // Owned ids to local indices, by binary search in a sorted copy.
  std::vector<std::pair<long, int>> local(owned_ids.size());
  for (std::size_t i = 0; i < owned_ids.size(); ++i) local[i] = {owned_ids[i], static_cast<int>(i)};
  std::sort(local.begin(), local.end());
  send_start_.push_back(0);
  recv_start_.push_back(0);
  for (int r = 0; r < P; ++r) {
    if (want[r] == 0 && asked[r] == 0) continue;
    peers_.push_back(r);
    for (int k = asked_at[r]; k < asked_at[r + 1]; ++k) {
      const auto it = std::lower_bound(local.begin(), local.end(), std::make_pair(requested[k], 0));
      MF_REQUIRE(it != local.end() && it->first == requested[k], "halo: rank ", r,
                 " asks for particle ", requested[k], ", which rank ", ranks.rank, " does not own");
      send_index_.push_back(it->second);
    }
    send_start_.push_back(static_cast<int>(send_index_.size()));
    recv_start_.push_back(want_at[r + 1]);
  }
}

void Halo::exchange_bytes(unsigned char* a, std::size_t item) const {
  const std::size_t peers = peers_.size();
  buf_.resize(send_index_.size() * item);
  for (std::size_t k = 0; k < send_index_.size(); ++k)
    std::memcpy(&buf_[k * item], a + static_cast<std::size_t>(send_index_[k]) * item, item);
  std::vector<MPI_Request>& req = requests_;
  req.resize(2 * peers);
  for (std::size_t p = 0; p < peers; ++p) {
    unsigned char* ghost = a + (static_cast<std::size_t>(owned_) + recv_start_[p]) * item;
    MPI_Irecv(ghost, static_cast<int>((recv_start_[p + 1] - recv_start_[p]) * item), MPI_BYTE,
              peers_[p], 17, ranks_.comm, &req[2 * p]);
    MPI_Isend(&buf_[send_start_[p] * item],
              static_cast<int>((send_start_[p + 1] - send_start_[p]) * item), MPI_BYTE, peers_[p],
              17, ranks_.comm, &req[2 * p + 1]);
  }
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
}

} // namespace mf::distribution
