#pragma once
// The one place the code meets PETSc. PetscSession initialises PETSc (and MPI) for the lifetime
// of a run; BlockLinearSystem is a distributed sparse system with 2 or 3 DOFs per node.
#include "meshfree/core/error.hpp"
#include <functional>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace mf::solvers {

/// An error that every rank has seen (see PetscSession::collective).
class CollectiveError : public Error {
public:
  using Error::Error;
};

class PetscSession {
public:
  /// Passes argc/argv to PETSc so that options after the program's own arguments apply.
  PetscSession(int* argc, char*** argv);
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm comm() const { return comm_; }

  /// The running session seen by this rank alone (MPI_COMM_SELF: rank 0 of 1), for work that
  /// every rank repeats whole so that each holds the one-rank result bit for bit. It leaves
  /// PETSc to the session it is made from, which must outlive it.
  static std::unique_ptr<const PetscSession> this_rank_alone();

  /// Runs `work` on every rank; if it fails on any rank, every rank throws a CollectiveError
  /// with the message of the lowest failing rank, so no rank is left waiting in a later
  /// collective call. Use it around work that can fail on some ranks only.
  void collective(const std::function<void()>& work) const;

  /// The PETSc options given (after --) that nothing has read so far, as "-name value": at the
  /// end of a run, a typo or an option of a solver the run does not use.
  std::vector<std::string> unused_options() const;

private:
  explicit PetscSession(MPI_Comm comm);
  MPI_Comm comm_ = MPI_COMM_WORLD;
  int rank_ = 0, size_ = 1;
  bool finalises_ = true; // the session that initialised PETSc
};

/// Contiguous block of node indices owned by `rank` out of `n` nodes on `size` ranks.
struct OwnedRange {
  int begin = 0, end = 0;
  bool owns(int node) const { return node >= begin && node < end; }
};
OwnedRange owned_nodes(int n, int rank, int size);
/// Rank that owns `node` under owned_nodes.
int owner_of(int node, int n, int size);

/// How the linear systems are solved unless PETSc options given after -- say otherwise.
/// - direct: a sparse factorisation by MUMPS (Cholesky for symmetric matrices, LU otherwise);
/// - multigrid: conjugate gradients (GMRES for a matrix that is not symmetric) preconditioned by
///   PETSc's smoothed-aggregation algebraic multigrid (GAMG; Vanek, Mandel & Brezina 1996), given
///   the rigid-body modes of the nodes as its near-null space (three in 2D, six in 3D; without
///   them the coarse spaces cannot represent rotation and the iterations grow with the size),
///   with the rows held by penalties solved exactly before and after each cycle (without that
///   the iterations grow with the penalty), stopped when the preconditioned residual falls below
///   `relative_tolerance` of its initial value.
struct LinearSolverSettings {
  bool multigrid = false;
  bool symmetric = true; // false for a Petrov-Galerkin form: LU, or GMRES with multigrid
  double relative_tolerance = 1e-12;
  /// multigrid: the dofs-per-node coordinates of each owned node in order (x, y or x, y, z)
  std::vector<double> coordinates;
  /// multigrid: the preconditioner inside the finest level's Chebyshev smoother. Point Jacobi
  /// suits finite elements (SOR costs them more time than it saves iterations); the wide
  /// stencils of 3D meshfree shape functions (a row couples hundreds of nodes) leave errors
  /// that Chebyshev over Jacobi does not damp, and over symmetric SOR does ([Adams, Brezina,
  /// Hu & Tuminaro 2003]; measured in README.md). The coarser levels keep Jacobi: their
  /// matrices have zero rows where an aggregate of held rows has no near-null modes, which SOR
  /// cannot invert.
  enum class FineSmoother { jacobi, sor };
  FineSmoother fine_smoother = FineSmoother::jacobi;
};

struct SolveReport {
  int iterations = 0;
  int converged_reason = 0;
  std::string reason_name;
  double residual_norm = 0.0;
  std::string solver; // KSP and PC type, and the factorisation package where one is used
};

/// The values of a matrix with `dofs` DOFs per node (2 or 3) in the matrix's own storage (PETSc's
/// AIJ arrays), on the pattern it was made with. For each owned node I in order, scalar rows
/// dofs I + c (c = 0 .. dofs - 1) each hold `dofs` values per block column J (columns dofs J ..
/// dofs J + dofs - 1) in column order: those of the owned nodes in `diagonal`, the others in
/// `off_diagonal` (null on one rank). Writing them in place spares a separate array of blocks
/// and its copy into the matrix: one matrix's worth of memory less to page in.
struct BlockValueArrays {
  double* diagonal = nullptr;
  double* off_diagonal = nullptr;
};

/// Fills the values of a matrix in place (zero on entry) and the right-hand side (dofs values per
/// owned node, sized and zero on entry).
using BlockFill = std::function<void(BlockValueArrays values, std::vector<double>& rhs)>;

/// A distributed sparse system with `dofs` DOFs per node (2 or 3) on the pattern of the owned
/// block rows: row_offset/columns give, for each owned node, the sorted global nodes it couples
/// to.
class BlockLinearSystem {
public:
  /// Makes the matrix on the pattern and lets `fill` write its values and the right-hand side.
  /// A symmetric positive definite system (elasticity held against rigid motion) is factorised
  /// by Cholesky, any other by LU.
  BlockLinearSystem(MPI_Comm comm, int node_count, OwnedRange owned,
                    const std::vector<int>& row_offset, const std::vector<int>& columns,
                    const BlockFill& fill, bool spd, const LinearSolverSettings& settings = {},
                    int dofs = 2);
  ~BlockLinearSystem();
  BlockLinearSystem(const BlockLinearSystem&) = delete;
  BlockLinearSystem& operator=(const BlockLinearSystem&) = delete;

  /// Solves with KSP as the settings say; every KSP/PC option given on the command line
  /// overrides them.
  SolveReport solve();
  /// Solves again for another right-hand side (dofs values per owned node), reusing the
  /// factorisation or the multigrid hierarchy of the first solve.
  SolveReport solve(const std::vector<double>& rhs);
  /// The owned entries of the solution (dofs per owned node).
  std::vector<double> solution() const;
  /// The whole solution vector on every rank.
  std::vector<double> solution_everywhere() const;
  /// Number of stored matrix entries over all ranks.
  double global_nonzeros() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace mf::solvers
