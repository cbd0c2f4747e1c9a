#pragma once
// Reductions and gathers over the ranks of a run: sums and extremes over points that each rank
// holds a share of, values collected on rank 0 for output, and the rank that holds the largest
// value. Every function is collective: each rank of `comm` calls it with the same counts.
#include <mpi.h>
#include <vector>

namespace mf::solvers {

/// Element-wise sum of `n` values over every rank, in place on every rank.
void sum_everywhere(MPI_Comm comm, double* values, int n);
double sum_everywhere(MPI_Comm comm, double value);
long sum_everywhere(MPI_Comm comm, long value);
/// Element-wise largest of `n` values over every rank, in place on every rank.
void max_everywhere(MPI_Comm comm, double* values, int n);
double max_everywhere(MPI_Comm comm, double value);

/// Element-wise sum over every rank, left in `values` on rank 0 (other ranks keep their own).
void sum_on_root(MPI_Comm comm, std::vector<double>& values);

/// Every rank's values, concatenated in rank order on rank 0 (empty on the other ranks).
std::vector<double> gather_on_root(MPI_Comm comm, const std::vector<double>& mine);

/// `values` of rank `root`, copied to every rank (resized there).
void broadcast(MPI_Comm comm, std::vector<double>& values, int root);

/// The peak resident memory of the largest rank and of all ranks together, in bytes.
struct PeakMemory {
  double largest_rank = 0.0, all_ranks = 0.0;
};
PeakMemory peak_memory(MPI_Comm comm);

/// The largest value over every rank, and the rank holding it (the lowest one on a tie).
struct RankMax {
  double value = 0.0;
  int rank = 0;
};
/// The largest `value`; the `n` values of `payload` (a position, say) of the rank that holds it
/// are copied to every rank.
RankMax max_with_location(MPI_Comm comm, double value, double* payload, int n);

/// Ends the run on every rank of `comm` with exit code `code`: for an error that reached this rank
/// only, while the others would wait for it in a collective call forever.
[[noreturn]] void abort_every_rank(MPI_Comm comm, int code);

} // namespace mf::solvers
