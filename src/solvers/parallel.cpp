#include "meshfree/solvers/parallel.hpp"
#include "meshfree/core/memory.hpp"
#include <cstdlib>

namespace mf::solvers {

void sum_everywhere(MPI_Comm comm, double* values, int n) {
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, comm);
}

double sum_everywhere(MPI_Comm comm, double value) {
  sum_everywhere(comm, &value, 1);
  return value;
}

long sum_everywhere(MPI_Comm comm, long value) {
  MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_LONG, MPI_SUM, comm);
  return value;
}

void max_everywhere(MPI_Comm comm, double* values, int n) {
  MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MAX, comm);
}

double max_everywhere(MPI_Comm comm, double value) {
  max_everywhere(comm, &value, 1);
  return value;
}

void sum_on_root(MPI_Comm comm, std::vector<double>& values) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int n = static_cast<int>(values.size());
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, values.data(), n, MPI_DOUBLE, MPI_SUM, 0, comm);
  else
    MPI_Reduce(values.data(), nullptr, n, MPI_DOUBLE, MPI_SUM, 0, comm);
}

std::vector<double> gather_on_root(MPI_Comm comm, const std::vector<double>& mine) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(size), displs(size, 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<double> all;
  if (rank == 0) {
    for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    all.resize(displs.back() + counts.back());
  }
  MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
              comm);
  return all;
}

void broadcast(MPI_Comm comm, std::vector<double>& values, int root) {
  long n = static_cast<long>(values.size());
  MPI_Bcast(&n, 1, MPI_LONG, root, comm);
  values.resize(static_cast<std::size_t>(n));
  MPI_Bcast(values.data(), static_cast<int>(n), MPI_DOUBLE, root, comm);
}

RankMax max_with_location(MPI_Comm comm, double value, double* payload, int n) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  struct {
    double value;
    int rank;
  } mine{value, rank}, top{0.0, 0};
  MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Bcast(payload, n, MPI_DOUBLE, top.rank, comm);
  return {top.value, top.rank};
}

void abort_every_rank(MPI_Comm comm, int code) {
  MPI_Abort(comm, code);
  std::abort(); // not reached: MPI_Abort ends the process, but is not declared noreturn
}

PeakMemory peak_memory(MPI_Comm comm) {
  const double mine = peak_resident_bytes();
  return {max_everywhere(comm, mine), sum_everywhere(comm, mine)};
}

} // namespace mf::solvers
