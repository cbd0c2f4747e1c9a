// The multigrid preconditioner of the iterative solves: GAMG with the penalty-held rows solved
// exactly before and after each cycle (see set_penalty_band_multigrid in petsc_detail.hpp).
#include "petsc_detail.hpp"
#include <exception>
#include <petscksp.h>
#include <vector>

namespace mf::solvers::detail {

namespace {

/// The preconditioner's state, rebuilt from A's values at each set-up (each Newton tangent).
struct PenaltyBand {
  PC multigrid = nullptr; // GAMG on A, with the options of the outer PC's prefix
  IS rows = nullptr;      // the penalty-held rows (global numbers, the owned ones on each rank)
  Mat held = nullptr;     // A restricted to rows x rows
  Mat coupling = nullptr; // A restricted to rows x all columns
  Mat columns = nullptr;  // A restricted to all rows x `rows`; null when A is symmetric
  KSP exact = nullptr;    // Cholesky of `held` (LU unless A is known to be symmetric)
  Vec r_held = nullptr, y_held = nullptr, z = nullptr, work = nullptr;
  PetscInt held_count = 0; // over all ranks
  bool sor_on_finest_level = false;
};

void destroy_band_parts(PenaltyBand& b) {
  if (b.rows) ISDestroy(&b.rows);
  if (b.held) MatDestroy(&b.held);
  if (b.coupling) MatDestroy(&b.coupling);
  if (b.columns) MatDestroy(&b.columns);
  if (b.exact) KSPDestroy(&b.exact);
  for (Vec* v : {&b.r_held, &b.y_held, &b.z, &b.work})
    if (*v) VecDestroy(v);
}

/// The rows of A held by penalties (penalty_held_rows), as a parallel index set of global rows.
IS held_row_set(Mat A) {
  const std::vector<char> held = penalty_held_rows(A);
  PetscInt first = 0;
  check(MatGetOwnershipRange(A, &first, nullptr), "MatGetOwnershipRange");
  std::vector<PetscInt> rows;
  for (std::size_t i = 0; i < held.size(); ++i)
    if (held[i]) rows.push_back(first + static_cast<PetscInt>(i));
  MPI_Comm comm;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(A), &comm), "PetscObjectGetComm");
  IS is;
  check(ISCreateGeneral(comm, static_cast<PetscInt>(rows.size()), rows.data(), PETSC_COPY_VALUES,
                        &is),
        "ISCreateGeneral");
  return is;
}

bool known_symmetric(Mat A) {
  PetscBool set = PETSC_FALSE, flag = PETSC_FALSE;
  check(MatIsSymmetricKnown(A, &set, &flag), "MatIsSymmetricKnown");
  if (set && flag) return true;
  check(MatIsSPDKnown(A, &set, &flag), "MatIsSPDKnown");
  return set && flag;
}

/// Extracts the held block and the held rows (and columns, for a matrix not known to be
/// symmetric) of A and factorises the block with MUMPS: the held rows of all ranks in one
/// factorisation, a few per node along the held edges.
void set_up_band(PenaltyBand& b, Mat A) {
  destroy_band_parts(b);
  b.rows = held_row_set(A);
  check(ISGetSize(b.rows, &b.held_count), "ISGetSize");
  if (b.held_count == 0) return;
  IS all;
  PetscInt first = 0, end = 0;
  check(MatGetOwnershipRange(A, &first, &end), "MatGetOwnershipRange");
  MPI_Comm comm;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(A), &comm), "PetscObjectGetComm");
  check(ISCreateStride(comm, end - first, first, 1, &all), "ISCreateStride");
  check(MatCreateSubMatrix(A, b.rows, b.rows, MAT_INITIAL_MATRIX, &b.held), "MatCreateSubMatrix");
  check(MatCreateSubMatrix(A, b.rows, all, MAT_INITIAL_MATRIX, &b.coupling),
        "MatCreateSubMatrix");
  const bool symmetric = known_symmetric(A);
  if (!symmetric)
    check(MatCreateSubMatrix(A, all, b.rows, MAT_INITIAL_MATRIX, &b.columns),
          "MatCreateSubMatrix");
  check(ISDestroy(&all), "ISDestroy");
  if (symmetric) check(MatSetOption(b.held, MAT_SPD, PETSC_TRUE), "MatSetOption(MAT_SPD)");
  check(KSPCreate(comm, &b.exact), "KSPCreate");
  check(KSPSetOperators(b.exact, b.held, b.held), "KSPSetOperators");
  // A prefix of its own, so that -ksp_ options (-ksp_converged_reason) address the outer solve.
  check(KSPSetOptionsPrefix(b.exact, "held_rows_"), "KSPSetOptionsPrefix");
  check(KSPSetType(b.exact, KSPPREONLY), "KSPSetType");
  PC pc;
  check(KSPGetPC(b.exact, &pc), "KSPGetPC");
  check(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetUp(b.exact), "KSPSetUp");
  check(MatCreateVecs(b.held, &b.y_held, &b.r_held), "MatCreateVecs");
  check(MatCreateVecs(A, &b.z, &b.work), "MatCreateVecs");
}

/// Marks `outer` failed when `inner` failed (a multigrid whose smoother met an indefinite level),
/// so that the KSP stops with the reason.
PetscErrorCode pass_failure(PC inner, PC outer) {
  PCFailedReason reason = PC_NOERROR;
  PetscCall(PCGetFailedReason(inner, &reason));
  if (reason != PC_NOERROR) PetscCall(PCSetFailedReason(outer, reason));
  return 0;
}

/// The finest level's smoother preconditioned by symmetric SOR (set after GAMG's set-up, which
/// makes the levels), unless the user chose the levels' preconditioner. The Chebyshev smoother
/// is made anew, so that it estimates its eigenvalue bounds with SOR rather than keep those it
/// estimated with Jacobi during the set-up; its other settings (steps, transform) stay.
PetscErrorCode use_sor_on_finest_level(PC multigrid) {
  const char* prefix = nullptr;
  PetscCall(PCGetOptionsPrefix(multigrid, &prefix));
  PetscBool chosen = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, prefix, "-mg_levels_pc_type", &chosen));
  PetscInt levels = 0;
  PetscCall(PCMGGetLevels(multigrid, &levels));
  if (chosen || levels < 2) return 0;
  KSP smoother;
  PetscCall(PCMGGetSmoother(multigrid, levels - 1, &smoother));
  PC sor;
  PetscCall(KSPGetPC(smoother, &sor));
  PetscBool is_sor = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(sor), PCSOR, &is_sor));
  if (is_sor) return 0;
  PetscCall(PCSetType(sor, PCSOR));
  PetscCall(KSPSetType(smoother, KSPRICHARDSON));
  PetscCall(KSPSetType(smoother, KSPCHEBYSHEV));
  return KSPSetFromOptions(smoother);
}

PetscErrorCode band_set_up(PC pc) {
  PenaltyBand* b = nullptr;
  PetscCall(PCShellGetContext(pc, &b));
  Mat A, P;
  PetscCall(PCGetOperators(pc, &A, &P));
  try {
    set_up_band(*b, P);
  } catch (const std::exception& e) {
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "%s", e.what());
  }
  if (!b->multigrid) {
    MPI_Comm comm;
    PetscCall(PetscObjectGetComm(reinterpret_cast<PetscObject>(pc), &comm));
    PetscCall(PCCreate(comm, &b->multigrid));
    const char* prefix = nullptr;
    PetscCall(PCGetOptionsPrefix(pc, &prefix));
    PetscCall(PCSetOptionsPrefix(b->multigrid, prefix));
    PetscCall(PCSetType(b->multigrid, PCGAMG));
    // Couplings below 1% of the diagonals' geometric mean are dropped from the aggregation
    // graph: the held rows (diagonals up to 10^6 E / h) form aggregates of their own instead of
    // joining their neighbours' (measured in README.md, "linear systems").
    PetscReal threshold[] = {0.01};
    PetscCall(PCGAMGSetThreshold(b->multigrid, threshold, 1));
    // The smoothers' eigenvalue bounds estimated by each smoother with its own preconditioner,
    // not taken from the aggregation's Jacobi-scaled estimate, which would not fit SOR.
    if (b->sor_on_finest_level) PetscCall(PCGAMGSetUseSAEstEig(b->multigrid, PETSC_FALSE));
    PetscCall(PCSetFromOptions(b->multigrid));
  }
  PetscCall(PCSetOperators(b->multigrid, A, P));
  PetscCall(PCSetUp(b->multigrid));
  if (b->sor_on_finest_level) PetscCall(use_sor_on_finest_level(b->multigrid));
  return pass_failure(b->multigrid, pc);
}

/// y_held += (A_held)^-1 (r - A y)_held, the residual taken on the held rows only.
PetscErrorCode correct_held_rows(PenaltyBand& b, Vec r, Vec y) {
  Vec r_rows;
  PetscCall(VecGetSubVector(r, b.rows, &r_rows));
  PetscCall(MatMult(b.coupling, y, b.r_held));
  PetscCall(VecAYPX(b.r_held, -1.0, r_rows));
  PetscCall(VecRestoreSubVector(r, b.rows, &r_rows));
  PetscCall(KSPSolve(b.exact, b.r_held, b.y_held));
  PetscCall(VecISAXPY(y, b.rows, 1.0, b.y_held));
  return 0;
}

/// Symmetric multiplicative: exact on the held rows, a multigrid cycle on the residual, exact on
/// the held rows again. The residual after the first held solve needs A y for a y that is zero
/// off the held rows: A's held columns (A's held rows, transposed, when A is symmetric).
PetscErrorCode band_apply(PC pc, Vec r, Vec y) {
  PenaltyBand* b = nullptr;
  PetscCall(PCShellGetContext(pc, &b));
  if (b->held_count == 0) {
    PetscCall(PCApply(b->multigrid, r, y));
    return pass_failure(b->multigrid, pc);
  }
  PetscCall(VecSet(y, 0.0));
  PetscCall(correct_held_rows(*b, r, y));
  if (b->columns)
    PetscCall(MatMult(b->columns, b->y_held, b->work));
  else
    PetscCall(MatMultTranspose(b->coupling, b->y_held, b->work));
  PetscCall(VecAYPX(b->work, -1.0, r));
  PetscCall(PCApply(b->multigrid, b->work, b->z));
  PetscCall(pass_failure(b->multigrid, pc));
  PetscCall(VecAXPY(y, 1.0, b->z));
  return correct_held_rows(*b, r, y);
}

PetscErrorCode band_view(PC pc, PetscViewer viewer) {
  PenaltyBand* b = nullptr;
  PetscCall(PCShellGetContext(pc, &b));
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "  penalty-held rows solved exactly (MUMPS Cholesky) around each cycle: %d\n",
      static_cast<int>(b->held_count)));
  if (b->multigrid) PetscCall(PCView(b->multigrid, viewer));
  return 0;
}

PetscErrorCode band_destroy(PC pc) {
  PenaltyBand* b = nullptr;
  PetscCall(PCShellGetContext(pc, &b));
  destroy_band_parts(*b);
  if (b->multigrid) PCDestroy(&b->multigrid);
  delete b;
  return 0;
}

} // namespace

void set_penalty_band_multigrid(PC pc, bool sor_on_finest_level) {
  check(PCSetType(pc, PCSHELL), "PCSetType");
  auto* band = new PenaltyBand;
  band->sor_on_finest_level = sor_on_finest_level;
  check(PCShellSetContext(pc, band), "PCShellSetContext");
  check(PCShellSetName(pc, kPenaltyBandMultigrid), "PCShellSetName");
  check(PCShellSetSetUp(pc, band_set_up), "PCShellSetSetUp");
  check(PCShellSetApply(pc, band_apply), "PCShellSetApply");
  check(PCShellSetView(pc, band_view), "PCShellSetView");
  check(PCShellSetDestroy(pc, band_destroy), "PCShellSetDestroy");
}

} // namespace mf::solvers::detail
