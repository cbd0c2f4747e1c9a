#pragma once
// A symmetric positive definite sparse system on one rank with 2 DOFs per node, given by the
// upper triangle of its 2x2 blocks (as SymmetricBlockSystem takes it), solved by conjugate
// gradients preconditioned by smoothed-aggregation multigrid (GAMG) whose near-null space is the
// rigid motions of the nodes.
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/solvers/symmetric_block_system.hpp"
#include <memory>
#include <string>
#include <vector>

namespace mf::solvers {

class MultigridBlockSystem {
public:
  /// Makes the whole matrix (AIJ, block size 2) from the upper triangle. `coordinates` are the
  /// nodes' (two per node); `held` marks the components (two per node) whose rows and columns
  /// are the identity's, zero in the near-null space. The solver reads the PETSc options that
  /// begin with `options_prefix`, which override CG + GAMG.
  MultigridBlockSystem(const UpperBlockRows& rows, const std::vector<double>& coordinates,
                       const std::vector<unsigned char>& held, const std::string& options_prefix);
  ~MultigridBlockSystem();
  MultigridBlockSystem(const MultigridBlockSystem&) = delete;
  MultigridBlockSystem& operator=(const MultigridBlockSystem&) = delete;

  /// Solves for the right-hand side (two values per node) until the residual's 2-norm is at most
  /// `relative_tolerance` times the right-hand side's, setting up the hierarchy on the first
  /// call. Stops with the reason when the solve does not converge.
  SolveReport solve(const std::vector<double>& rhs, double relative_tolerance);
  /// The solution of the last solve (two values per node).
  std::vector<double> solution() const;
  /// Wall time of the multigrid set-up of the first solve.
  double setup_seconds() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether the PETSc options ask the solver under the prefix for GAMG (-<prefix>pc_type gamg),
/// which needs the whole matrix that MultigridBlockSystem makes.
bool multigrid_asked(const std::string& options_prefix);

} // namespace mf::solvers
