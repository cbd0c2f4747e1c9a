#pragma once
// Newton-Raphson on a distributed system with 2 or 3 DOFs per node through PETSc SNES. The caller
// supplies the residual and the Jacobian as block rows on the exact pattern of the owned nodes
// (the same rows the elastic solver assembles); SNES does the iteration (newtonls with a line
// search by default), KSP the linear solves (LinearSolverSettings); every -snes_/-ksp_/-pc_ option
// on the command line overrides the defaults.
#include "meshfree/solvers/petsc_session.hpp"
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mf::solvers {

struct NewtonSettings {
  /// Converged when |R| <= tolerance * |F|, with F the force scale the residual reports
  /// (internal and external forces together), or when |R| is within the round-off floor the
  /// residual reports (penalty terms put it above tolerance * |F|; see the source).
  double tolerance = 1e-8;
  int max_iterations = 20;
  /// Modified Newton: the factorised tangent is kept, from iteration to iteration and from one
  /// solve to the next, while each iteration brings |R| to at most this fraction of the one
  /// before; an iteration that does not builds and factorises a new one for the next. 0: a new
  /// tangent at every iteration (Newton's method).
  double keep_tangent = 0.0;
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  int linear_iterations = 0;
  int linear_iterations_max = 0; // the most of one Newton iteration's linear solve
  std::string reason;            // SNES converged reason, e.g. CONVERGED_FNORM_ABS
  std::string failure; // what went wrong in a residual or Jacobian evaluation, if anything
  /// The tangents built and factorised (Newton's method: one an iteration, and one more for a last
  /// correction too small to count as an iteration).
  int tangents = 0;
  std::vector<double> residual; // |R| at the start and after each iteration
  std::vector<double> scale;    // the force scale |F| at the same points
};

/// What a residual evaluation reports besides R, as this rank's shares of squared norms: the
/// force scale |F|^2, and the round-off floor of R, the sum over rows of (eps * the sum of the
/// magnitudes of the terms that make the row)^2, below which |R| cannot be resolved.
struct ResidualSums {
  double scale_squared = 0.0;
  double floor_squared = 0.0;
};

/// Residual R(d) on the owned rows (dofs values per owned node) and this rank's ResidualSums.
/// `d` has the full length dofs N; the entries of the nodes named in `needed` (and the owned ones)
/// hold the current iterate. Throwing an exception marks the point as outside the domain of the
/// residual (a failed return mapping, a NaN): SNES then stops and the message is reported.
using ResidualFunction =
    std::function<void(const std::vector<double>& d, double* residual, ResidualSums& sums)>;
/// Jacobian dR/dd, written in place into the matrix's values (BlockValueArrays, zero on entry).
using JacobianFunction = std::function<void(const std::vector<double>& d, BlockValueArrays values)>;

class NonlinearBlockSystem {
public:
  /// `row_offset`/`columns`: for each owned node, the sorted global nodes it couples to.
  /// `needed`: the nodes whose values the residual and Jacobian read (besides the owned ones).
  /// `dofs`: the DOFs per node, 2 or 3.
  NonlinearBlockSystem(MPI_Comm comm, int node_count, OwnedRange owned,
                       const std::vector<int>& row_offset, const std::vector<int>& columns,
                       const std::vector<int>& needed, ResidualFunction residual,
                       JacobianFunction jacobian, const LinearSolverSettings& linear = {},
                       int dofs = 2);
  ~NonlinearBlockSystem();
  NonlinearBlockSystem(const NonlinearBlockSystem&) = delete;
  NonlinearBlockSystem& operator=(const NonlinearBlockSystem&) = delete;

  /// Newton from the guess in `d` (owned entries read); on return `d` holds the last iterate
  /// in the owned and needed entries, whether or not it converged.
  NewtonReport solve(std::vector<double>& d, const NewtonSettings& settings);

  /// The owned entries of `d` collected into the full vector on rank 0 (empty on other ranks).
  std::vector<double> gather_on_root(const std::vector<double>& d) const;

  /// "newtonls(cp) + preonly/cholesky/mumps".
  std::string description() const;

  struct Impl; // PETSc objects and the callbacks' state (defined in the source file)

private:
  std::unique_ptr<Impl> impl_;
};

} // namespace mf::solvers
