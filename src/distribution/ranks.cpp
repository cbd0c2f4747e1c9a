#include "meshfree/distribution/ranks.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/solvers/parallel.hpp"

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

double Ranks::sum(double value) const {
  if (serial()) return value;
  return solvers::sum_everywhere(comm, value);
}

long Ranks::sum(long value) const {
  if (serial()) return value;
  return solvers::sum_everywhere(comm, value);
}

void Ranks::sum(double* values, int n) const {
  if (!serial()) solvers::sum_everywhere(comm, values, n);
}

double Ranks::max(double value) const {
  if (serial()) return value;
  return solvers::max_everywhere(comm, value);
}

double Ranks::min(double value) const {
  return -max(-value);
}

int Ranks::rank_of_min(double value) const {
  if (serial()) return 0;
  struct {
    double value;
    int rank;
  } mine{value, rank}, best{};
  MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm);
  return best.rank;
}

void Ranks::broadcast(double* values, int n, int root) const {
  if (!serial()) MPI_Bcast(values, n, MPI_DOUBLE, root, comm);
}

std::vector<double> to_id_blocks(const Ranks& ranks, const IdBlocks& blocks,
                                 const std::vector<long>& ids, int n,
                                 const std::vector<double>& values, int per) {
  const int R = ranks.size;
  const long first = blocks.first(ranks.rank);
  std::vector<double> out(static_cast<std::size_t>(blocks.first(ranks.rank + 1) - first) * per);
  if (ranks.serial()) {
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < per; ++c)
        out[static_cast<std::size_t>(ids[k] - first) * per + c] =
            values[static_cast<std::size_t>(k) * per + c];
    return out;
  }
  // Sorted by destination rank: ids and values.
  std::vector<int> count(R, 0), at(R + 1, 0);
  std::vector<int> dest(n);
  for (int k = 0; k < n; ++k) ++count[dest[k] = blocks.owner(ids[k])];
  for (int r = 0; r < R; ++r) at[r + 1] = at[r] + count[r];
  std::vector<long> send_ids(n);
  std::vector<double> send_values(static_cast<std::size_t>(n) * per);
  std::vector<int> next(at.begin(), at.end() - 1);
  for (int k = 0; k < n; ++k) {
    const int slot = next[dest[k]]++;
    send_ids[slot] = ids[k];
    for (int c = 0; c < per; ++c)
      send_values[static_cast<std::size_t>(slot) * per + c] =
          values[static_cast<std::size_t>(k) * per + c];
  }
  std::vector<int> recv(R), recv_at(R + 1, 0);
  MPI_Alltoall(count.data(), 1, MPI_INT, recv.data(), 1, MPI_INT, ranks.comm);
  for (int r = 0; r < R; ++r) recv_at[r + 1] = recv_at[r] + recv[r];
  std::vector<long> got_ids(recv_at[R]);
  MPI_Alltoallv(send_ids.data(), count.data(), at.data(), MPI_LONG, got_ids.data(), recv.data(),
                recv_at.data(), MPI_LONG, ranks.comm);
  // The values: `per` times the counts and offsets.
  for (int r = 0; r <= R; ++r) {
    if (r < R) count[r] *= per, recv[r] *= per;
    at[r] *= per, recv_at[r] *= per;
  }
  std::vector<double> got(static_cast<std::size_t>(recv_at[R]));
  MPI_Alltoallv(send_values.data(), count.data(), at.data(), MPI_DOUBLE, got.data(), recv.data(),
                recv_at.data(), MPI_DOUBLE, ranks.comm);
  MF_REQUIRE(static_cast<long>(got_ids.size()) * per == static_cast<long>(out.size()),
             "to_id_blocks: rank ", ranks.rank, " received ", got_ids.size(),
             " particles for a block of ", out.size() / per);
  for (std::size_t k = 0; k < got_ids.size(); ++k)
    for (int c = 0; c < per; ++c)
      out[static_cast<std::size_t>(got_ids[k] - first) * per + c] = got[k * per + c];
  return out;
}

} // namespace mf::distribution
