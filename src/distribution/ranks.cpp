#include "meshfree/distribution/ranks.hpp"

namespace mf::distribution {

Ranks Ranks::of(MPI_Comm comm) {
  Ranks r;
  r.comm = comm;
  MPI_Comm_rank(comm, &r.rank);
  MPI_Comm_size(comm, &r.size);
  return r;
}

int IdBlocks::owner(long id) const {
  // first(r) <= id < first(r + 1); the estimate is off by at most one either way.
  int r = static_cast<int>((static_cast<__int128>(id) * ranks) / (total > 0 ? total : 1));
  if (r >= ranks) r = ranks - 1;
  while (r > 0 && first(r) > id) --r;
  while (r + 1 < ranks && first(r + 1) <= id) ++r;
  return r;
}

} // namespace mf::distribution
