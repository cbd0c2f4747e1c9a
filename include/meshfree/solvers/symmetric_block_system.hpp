#pragma once
// A symmetric positive definite sparse system on one rank with 2 DOFs per node, given by the
// upper triangle of its 2x2 blocks, factorised once by a sparse Cholesky and solved for as many
// right-hand sides as wanted.
#include "meshfree/solvers/petsc_session.hpp"
#include <memory>
#include <string>
#include <vector>

namespace mf::solvers {

/// The upper triangle of a symmetric matrix of 2x2 blocks in block compressed rows: block row i
/// holds its diagonal block first, then the blocks of the nodes j > i it couples to, in
/// increasing j. Each block's 4 values are stored row by row.
struct UpperBlockRows {
  std::vector<int> offset{0}; // block row i: slots offset[i] .. offset[i + 1] - 1
  std::vector<int> column;    // the node of each slot
  std::vector<double> value;  // 4 per slot
  int nodes() const { return static_cast<int>(offset.size()) - 1; }
};

class SymmetricBlockSystem {
public:
  /// Makes the matrix from the rows; its solver reads the PETSc options that begin with
  /// `options_prefix`.
  SymmetricBlockSystem(const UpperBlockRows& rows, const std::string& options_prefix);
  ~SymmetricBlockSystem();
  SymmetricBlockSystem(const SymmetricBlockSystem&) = delete;
  SymmetricBlockSystem& operator=(const SymmetricBlockSystem&) = delete;

  /// Solves for the right-hand side (two values per node), factorising on the first call;
  /// options of the command line with the prefix (pd_: -pd_pc_factor_mat_solver_type cholmod)
  /// override the default, MUMPS's Cholesky. Stops with the reason when the factorisation or the solve
  /// fails.
  SolveReport solve(const std::vector<double>& rhs);
  /// The solution of the last solve (two values per node).
  std::vector<double> solution() const;
  /// Wall time of the factorisation (symbolic and numeric) of the first solve.
  double factorisation_seconds() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace mf::solvers
