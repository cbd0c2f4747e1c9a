#pragma once
// The MPI ranks an explicit run is spread over, and the split of a body's global particle ids
// into one contiguous block per rank. Particles are numbered along a space-filling curve before
// they are split, so a block of ids is a compact piece of the body:
// the decomposition balances particle counts exactly and keeps each rank's halo small, as the
// space-filling-curve partitioners of p4est and Zoltan's HSFC do.
#include <mpi.h>
#include <vector>

namespace mf::distribution {

struct Ranks {
  MPI_Comm comm = MPI_COMM_SELF;
  int rank = 0;
  int size = 1;
  static Ranks of(MPI_Comm comm);
  bool serial() const { return size == 1; }
  // Reductions over every rank (collective; no message on one rank).
  double sum(double value) const;
  long sum(long value) const;
  void sum(double* values, int n) const;
  double max(double value) const;
  double min(double value) const;
  /// The rank holding the smallest value (the lowest such rank on a tie).
  int rank_of_min(double value) const;
  /// `n` values of rank `root`, copied to every rank.
  void broadcast(double* values, int n, int root) const;
};

/// Ids 0 .. total-1 split into `ranks` contiguous blocks whose sizes differ by at most one.
struct IdBlocks {
  long total = 0;
  int ranks = 1;
  /// The first id of rank r's block (r = ranks gives total).
  long first(int r) const { return static_cast<long>((static_cast<__int128>(total) * r) / ranks); }
  /// The rank whose block holds `id`.
  int owner(long id) const;
};

/// Per-particle values of particles spread over the ranks in any way (this rank's: the first n of
/// `ids`, `per` values each in `values`), returned as this rank's block of `blocks` in id order:
/// the layout of a field file written by id blocks. Collective.
std::vector<double> to_id_blocks(const Ranks& ranks, const IdBlocks& blocks,
                                 const std::vector<long>& ids, int n,
                                 const std::vector<double>& values, int per);

} // namespace mf::distribution
