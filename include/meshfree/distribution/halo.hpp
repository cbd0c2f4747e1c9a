#pragma once
// Ghost (halo) particles kept up to date from their owners, as LAMMPS's Comm::forward_comm does:
// each rank holds its owned particles first and then copies of the other ranks' particles its
// own ones interact with, grouped by owner rank. exchange() sends every owned value a neighbour
// rank holds a copy of and receives the copies' values straight into the ghost slots.
#include "meshfree/distribution/ranks.hpp"
#include <cstddef>
#include <vector>

namespace mf::distribution {

class Halo {
public:
  /// No ghost: exchange() does nothing.
  Halo() = default;
  /// `owned_ids`: the global ids of this rank's owned particles in local order. `ghost_ids`,
  /// `ghost_owner`: those of its ghost particles (local index owned_ids.size() + k) and their
  /// owners, sorted by owner rank. Collective over `ranks`.
  Halo(const Ranks& ranks, const std::vector<long>& owned_ids, const std::vector<long>& ghost_ids,
       const std::vector<int>& ghost_owner);

  /// Copies the owners' values into the ghost slots of `a` (`per` values per particle).
  /// Collective.
  template <class T> void exchange(std::vector<T>& a, int per = 1) const {
    if (peers_.empty()) return;
    exchange_bytes(reinterpret_cast<unsigned char*>(a.data()), per * sizeof(T));
  }

  int ghosts() const { return ghosts_; }
  /// Particles sent by this rank in one exchange (a particle sent to two ranks counts twice).
  long sent() const { return static_cast<long>(send_index_.size()); }
  const Ranks& ranks() const { return ranks_; }

private:
  void exchange_bytes(unsigned char* a, std::size_t item) const;
  Ranks ranks_;
  int owned_ = 0, ghosts_ = 0;
  std::vector<int> peers_;                 // ranks exchanged with, increasing
  std::vector<int> send_start_;            // per peer + 1: offsets into send_index_
  std::vector<int> send_index_;            // owned local indices sent, grouped by peer
  std::vector<int> recv_start_;            // per peer + 1: ghost offsets (from owned_)
  mutable std::vector<unsigned char> buf_; // scratch: packed values to send
  mutable std::vector<MPI_Request> requests_;
};

} // namespace mf::distribution
