#pragma once
// Pieces shared by the PETSc wrappers of this module; included by src/solvers/*.cpp only.
#include "meshfree/core/error.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include <functional>
#include <petscksp.h>
#include <set>
#include <string>
#include <vector>

namespace mf::solvers::detail {

/// What PETSc said of its last error, on one line (its error handler keeps it instead of
/// printing its traceback): "" when nothing was said.
std::string last_petsc_error();

/// Stops with "PETSc error N in WHAT: <PETSc's own message>": one line, which names the option
/// when an option was bad (-ksp_type bogus: "Unable to find requested KSP type bogus").
inline void check(PetscErrorCode ierr, const char* what) {
  if (!ierr) return;
  const std::string said = last_petsc_error();
  fail("PETSc error ", static_cast<int>(ierr), " in ", what, said.empty() ? "" : ": " + said,
       " (check the PETSc options given after --)");
}

/// A distributed AIJ matrix (block size `dofs`, 2 or 3 DOFs per node) of zeros with the exact
/// pattern of the owned block rows: block row I gives scalar rows dofs I .. dofs I + dofs - 1,
/// block column J the columns dofs J .. dofs J + dofs - 1. Its storage is checked to be in the
/// order BlockValueArrays describes.
Mat create_block_matrix(MPI_Comm comm, int node_count, OwnedRange owned,
                        const std::vector<int>& row_offset, const std::vector<int>& columns,
                        int dofs);

/// Lets `write` change the values of a matrix made by create_block_matrix in place (zero when it
/// is new); the arrays go back to the matrix, marked as changed, whether or not `write` throws.
void write_block_values(Mat A, const std::function<void(BlockValueArrays)>& write);

/// The default linear solver of `settings` for the operator A, set before the command-line
/// options so that every -ksp_/-pc_ option overrides it: MUMPS (Cholesky for symmetric
/// matrices, settings.symmetric, LU otherwise), or CG/GMRES with GAMG and A's near-null space set
/// to the rigid-body modes of settings.coordinates. An iterative solve reports its progress on
/// stderr every 10 s and stops early when its residual stagnates.
void set_default_solver(KSP ksp, Mat A, const LinearSolverSettings& settings);

/// The owned rows of A held by a penalty: a diagonal above kHeldRatio times the median diagonal
/// of the owned rows (one flag per owned row).
std::vector<char> penalty_held_rows(Mat A);

/// What describe() names the preconditioner of set_penalty_band_multigrid.
inline constexpr const char* kPenaltyBandMultigrid = "gamg+held-rows";

/// Makes pc the multigrid preconditioner of the iterative solves: a V-cycle of GAMG (with the
/// options of pc's prefix, -pc_gamg_*, -mg_levels_*) between two exact solves on the
/// penalty-held rows, symmetric multiplicative (B = S + (I - S A) G (I - A S), S the exact
/// inverse on the held rows, G the cycle). The held rows carry penalties up to 10^6 times the
/// stiffness through shape functions that couple them along the edge; their errors that the
/// penalty does not stiffen are left by the Jacobi-scaled smoother and not represented in the
/// coarse spaces (whose modes are zero there), so the cycle alone converged ever slower as the
/// penalty grew ([Lee, Wu, Xu & Zikatanov 2007]; the symmetric product as in [Xu 1992]). The
/// held rows are found anew from the matrix's values at each set-up. `sor_on_finest_level`:
/// the finest level's Chebyshev smoother preconditioned by symmetric SOR instead of Jacobi
/// (LinearSolverSettings::fine_smoother), unless -mg_levels_pc_type is given.
void set_penalty_band_multigrid(PC pc, bool sor_on_finest_level);

/// A's near-null space for GAMG, from A's values: the rigid-body modes of the nodes
/// (MatNullSpaceCreateRigidBody on `coordinates`, A's block size of them per owned node: the
/// translations and the in-plane rotation in 2D, three translations and three rotations in 3D)
/// with the penalty-held rows set to zero. Those rows'
/// values are fixed by their penalties, so the modes that are nearly free of energy are zero
/// there; the full rigid-body modes would make GAMG build coarse functions that move them, at
/// the cost of the penalty (smoothed aggregation interpolates the near-kernel it is given,
/// [Vanek, Mandel & Brezina 1996]). Set again whenever A's values change (each Newton tangent).
void set_near_null_space(Mat A, const std::vector<double>& coordinates);

/// Sets the `held` entries of every mode to zero and makes the modes orthonormal again (Gram-
/// Schmidt, as MatNullSpaceCreate requires); a mode left with nothing is destroyed and dropped.
void zero_held_rows(std::vector<Vec>& modes, const std::vector<char>& held);

/// What to try when the multigrid solver does not converge.
inline constexpr const char* kMultigridHint =
    "try linear_solver.type: direct (MUMPS), or GAMG options after -- (-pc_gamg_threshold)";

/// Why the last solve of a KSP set up by set_default_solver stopped early: its residual
/// stagnated (see kStagnationWindow in petsc_detail.cpp); "" when it did not.
std::string stagnation_note(KSP ksp);

/// The most iterations one solve of a KSP set up by set_default_solver took since the last call
/// (-1 when -ksp_convergence_test replaced the code's test).
int take_longest_solve(KSP ksp);

/// Names (without the '-') of the options the code itself puts in PETSc's database as defaults,
/// which are not the user's and so never reported unused.
std::set<std::string>& options_set_by_code();

/// The whole of a distributed vector on every rank (`everywhere`) or on rank 0 alone (empty
/// elsewhere).
std::vector<double> gather(Vec x, bool everywhere);

/// "preonly/cholesky/mumps": KSP type, PC type and factorisation package.
std::string describe(KSP ksp);

/// What a finished KSPSolve reports: its iterations, its converged reason and the reason's name,
/// and the solver (`describe`); the residual is the caller's to measure.
SolveReport solve_report(KSP ksp);

} // namespace mf::solvers::detail
