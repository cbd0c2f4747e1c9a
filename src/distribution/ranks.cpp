#include "meshfree/distribution/ranks.hpp"
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

} // namespace mf::distribution
