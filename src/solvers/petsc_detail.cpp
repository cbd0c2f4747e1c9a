#include "petsc_detail.hpp"
#include "meshfree/core/progress.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

namespace mf::solvers::detail {

namespace {

/// The diagonal (owned columns) and off-diagonal parts of A: A itself and none on one rank.
struct LocalParts {
  Mat diagonal = nullptr, off_diagonal = nullptr;
  const PetscInt* off_columns = nullptr; // global column of each off-diagonal local column
};

LocalParts local_parts(Mat A) {
  PetscBool mpi = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &mpi),
        "PetscObjectTypeCompare");
  LocalParts p;
  if (!mpi) {
    p.diagonal = A;
    return p;
  }
  check(MatMPIAIJGetSeqAIJ(A, &p.diagonal, &p.off_diagonal, &p.off_columns), "MatMPIAIJGetSeqAIJ");
  return p;
}

/// Inserts zeros on the pattern, a scalar row at a time, and assembles A.
void insert_pattern(Mat A, OwnedRange owned, const std::vector<int>& row_offset,
                    const std::vector<int>& columns, int dofs) {
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> zeros;
  for (int i = 0; i < owned.end - owned.begin; ++i) {
    const int n = row_offset[i + 1] - row_offset[i];
    cols.resize(dofs * n);
    zeros.assign(dofs * n, 0.0);
    for (int q = 0; q < n; ++q)
      for (int c = 0; c < dofs; ++c)
        cols[dofs * q + c] = dofs * static_cast<PetscInt>(columns[row_offset[i] + q]) + c;
    for (int comp = 0; comp < dofs; ++comp) {
      const PetscInt row = dofs * static_cast<PetscInt>(owned.begin + i) + comp;
      check(MatSetValues(A, 1, &row, dofs * n, cols.data(), zeros.data(), INSERT_VALUES),
            "MatSetValues");
    }
  }
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

/// Requires A's storage to hold the pattern in BlockValueArrays' order: in each scalar row the
/// owned block columns in one part and the others in the other, both in column order. PETSc's
/// AIJ matrices keep it so (sorted columns; the off-diagonal part numbered in the order of its
/// global columns); the check, one pass over the column indices, guards the values written in
/// place against a PETSc that stored them otherwise.
void require_storage_order(Mat A, OwnedRange owned, const std::vector<int>& row_offset,
                           const std::vector<int>& columns, int dofs) {
  const LocalParts p = local_parts(A);
  PetscInt nd = 0, no = 0;
  const PetscInt *id = nullptr, *jd = nullptr, *io = nullptr, *jo = nullptr;
  PetscBool done = PETSC_FALSE;
  check(MatGetRowIJ(p.diagonal, 0, PETSC_FALSE, PETSC_FALSE, &nd, &id, &jd, &done), "MatGetRowIJ");
  bool ok = done && nd == dofs * (owned.end - owned.begin);
  if (p.off_diagonal) {
    check(MatGetRowIJ(p.off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &no, &io, &jo, &done),
          "MatGetRowIJ");
    ok = ok && done && no == nd;
  }
  for (int i = 0; ok && i < owned.end - owned.begin; ++i)
    for (int comp = 0; ok && comp < dofs; ++comp) {
      const int r = dofs * i + comp;
      PetscInt kd = id[r], ko = io ? io[r] : 0;
      for (int k = row_offset[i]; ok && k < row_offset[i + 1]; ++k)
        for (int c = 0; ok && c < dofs; ++c) {
          const PetscInt column = dofs * static_cast<PetscInt>(columns[k]) + c;
          if (owned.owns(columns[k]))
            ok = kd < id[r + 1] && jd[kd++] == column - dofs * static_cast<PetscInt>(owned.begin);
          else
            ok = io && ko < io[r + 1] && p.off_columns[jo[ko++]] == column;
        }
      ok = ok && kd == id[r + 1] && (!io || ko == io[r + 1]);
    }
  check(MatRestoreRowIJ(p.diagonal, 0, PETSC_FALSE, PETSC_FALSE, &nd, &id, &jd, &done),
        "MatRestoreRowIJ");
  if (p.off_diagonal)
    check(MatRestoreRowIJ(p.off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &no, &io, &jo, &done),
          "MatRestoreRowIJ");
  MF_REQUIRE(ok, "block matrix: PETSc does not store the pattern in the order the values are "
                 "written in (owned columns, then the others, each in column order)");
}

} // namespace

Mat create_block_matrix(MPI_Comm comm, int node_count, OwnedRange owned,
                        const std::vector<int>& row_offset, const std::vector<int>& columns,
                        int dofs) {
  const int rows = owned.end - owned.begin;
  MF_REQUIRE(dofs == 2 || dofs == 3, "block matrix: ", dofs, " DOFs per node (2 or 3 are made)");
  MF_REQUIRE(static_cast<int>(row_offset.size()) == rows + 1,
             "block matrix: inconsistent block rows");
  // Exact preallocation in blocks: those in the owned columns (the diagonal part) and the rest.
  std::vector<PetscInt> diagonal(rows, 0), off_diagonal(rows, 0);
  for (int i = 0; i < rows; ++i)
    for (int k = row_offset[i]; k < row_offset[i + 1]; ++k)
      ++(owned.owns(columns[k]) ? diagonal : off_diagonal)[i];
  const PetscInt local = dofs * static_cast<PetscInt>(rows),
                 global = dofs * static_cast<PetscInt>(node_count);
  Mat A;
  check(MatCreate(comm, &A), "MatCreate");
  check(MatSetSizes(A, local, local, global, global), "MatSetSizes");
  check(MatSetBlockSize(A, dofs), "MatSetBlockSize");
  check(MatSetType(A, MATAIJ), "MatSetType");
  check(MatXAIJSetPreallocation(A, dofs, diagonal.data(), off_diagonal.data(), nullptr, nullptr),
        "MatXAIJSetPreallocation");
  insert_pattern(A, owned, row_offset, columns, dofs);
  // Later value updates must stay on this pattern.
  check(MatSetOption(A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  require_storage_order(A, owned, row_offset, columns, dofs);
  return A;
}

void write_block_values(Mat A, const std::function<void(BlockValueArrays)>& write) {
  const LocalParts p = local_parts(A);
  PetscScalar *d = nullptr, *o = nullptr;
  check(MatSeqAIJGetArray(p.diagonal, &d), "MatSeqAIJGetArray");
  if (p.off_diagonal) check(MatSeqAIJGetArray(p.off_diagonal, &o), "MatSeqAIJGetArray");
  std::exception_ptr error;
  try {
    write({d, o});
  } catch (...) {
    error = std::current_exception();
  }
  check(MatSeqAIJRestoreArray(p.diagonal, &d), "MatSeqAIJRestoreArray");
  if (p.off_diagonal) check(MatSeqAIJRestoreArray(p.off_diagonal, &o), "MatSeqAIJRestoreArray");
  // Assembling A (nothing is stashed) marks it as changed, and drops what PETSc keeps of the old
  // values (the inverted diagonals of its smoothers).
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  if (error) std::rethrow_exception(error);
}

namespace {

/// Sets PETSc option -name to `value` unless the user gave it, and marks it as the code's (not
/// reported among the unused options).
void default_option(const std::string& name, const char* value) {
  const std::string key = "-" + name;
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, key.c_str(), &set), "PetscOptionsHasName");
  if (set) return;
  check(PetscOptionsSetValue(nullptr, key.c_str(), value), "PetscOptionsSetValue");
  options_set_by_code().insert(name);
}

} // namespace

/// A row is held by a penalty when its diagonal exceeds kHeldRatio times the median diagonal
/// of the owned rows. In 2D an elastic stiffness diagonal is about E t whatever the spacing, and
/// a penalty alpha = beta E / h adds about beta E t phi_I^2 to the rows of the nodes that carry
/// a boundary point, so the held rows stand apart by the penalty factor beta. In 3D the
/// diagonal is about E h and the same penalty over a face adds about beta E h phi_I^2 (its
/// points weigh areas of order h^2): the same ratio. Ten: rows whose penalty outweighs their
/// stiffness tenfold are solved exactly by the multigrid preconditioner
/// (set_penalty_band_multigrid); below that the smoothers handle them. A material over ten times
/// stiffer than the median row would count as held too: solved exactly, at the cost of its
/// factorisation.
constexpr double kHeldRatio = 10.0;

std::vector<char> penalty_held_rows(Mat A) {
  Vec d;
  check(MatCreateVecs(A, &d, nullptr), "MatCreateVecs");
  check(MatGetDiagonal(A, d), "MatGetDiagonal");
  PetscInt n = 0;
  check(VecGetLocalSize(d, &n), "VecGetLocalSize");
  const PetscScalar* a;
  check(VecGetArrayRead(d, &a), "VecGetArrayRead");
  std::vector<double> diagonal(a, a + n);
  check(VecRestoreArrayRead(d, &a), "VecRestoreArrayRead");
  check(VecDestroy(&d), "VecDestroy");
  std::vector<char> held(diagonal.size(), 0);
  if (diagonal.empty()) return held;
  std::vector<double> sorted(diagonal);
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  for (std::size_t i = 0; i < diagonal.size(); ++i)
    held[i] = median > 0.0 && diagonal[i] > kHeldRatio * median;
  return held;
}

namespace {

void set_direct_solver(KSP ksp, bool symmetric) {
  // Penalty terms (alpha ~ 1e12) make the matrices too ill-conditioned for unpreconditioned
  // Krylov methods, so a direct solve is the safe default; Cholesky on symmetric systems takes
  // about 3/4 of the time of LU (80,000 DOFs: 2.9 s against 3.8 s).
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  // MUMPS sizes its work space from an estimate plus ICNTL(14) percent (PETSc's default 20);
  // distributed Cholesky of penalty-constrained matrices can exceed that (INFOG(1) = -9), so
  // allow 100 percent unless the user chose a value.
  default_option("mat_mumps_icntl_14", "100");
}

/// Copies of the rigid-body modes of the nodes, one entry per owned coordinate, `dofs`
/// coordinates per node (MatNullSpaceCreateRigidBody): the two translations and the in-plane
/// rotation in 2D, the three translations and three rotations in 3D.
std::vector<Vec> rigid_body_modes(MPI_Comm comm, const std::vector<double>& coordinates,
                                  PetscInt dofs) {
  Vec x;
  check(VecCreateMPI(comm, static_cast<PetscInt>(coordinates.size()), PETSC_DECIDE, &x),
        "VecCreateMPI");
  check(VecSetBlockSize(x, dofs), "VecSetBlockSize");
  PetscScalar* v;
  check(VecGetArray(x, &v), "VecGetArray");
  std::copy(coordinates.begin(), coordinates.end(), v);
  check(VecRestoreArray(x, &v), "VecRestoreArray");
  MatNullSpace rigid;
  check(MatNullSpaceCreateRigidBody(x, &rigid), "MatNullSpaceCreateRigidBody");
  PetscBool has_constant = PETSC_FALSE;
  PetscInt n = 0;
  const Vec* vectors = nullptr;
  check(MatNullSpaceGetVecs(rigid, &has_constant, &n, &vectors), "MatNullSpaceGetVecs");
  std::vector<Vec> modes(static_cast<std::size_t>(n));
  for (PetscInt k = 0; k < n; ++k) {
    check(VecDuplicate(vectors[k], &modes[k]), "VecDuplicate");
    check(VecCopy(vectors[k], modes[k]), "VecCopy");
  }
  check(MatNullSpaceDestroy(&rigid), "MatNullSpaceDestroy");
  check(VecDestroy(&x), "VecDestroy");
  return modes;
}

} // namespace

/// Sets the `held` entries of every mode to zero and makes the modes orthonormal again (Gram-
/// Schmidt, as MatNullSpaceCreate requires); a mode left with nothing (every row held) is
/// dropped.
void zero_held_rows(std::vector<Vec>& modes, const std::vector<char>& held) {
  std::vector<Vec> kept;
  for (Vec m : modes) {
    PetscScalar* v;
    check(VecGetArray(m, &v), "VecGetArray");
    for (std::size_t i = 0; i < held.size(); ++i)
      if (held[i]) v[i] = 0.0;
    check(VecRestoreArray(m, &v), "VecRestoreArray");
    for (Vec q : kept) {
      PetscScalar dot = 0.0;
      check(VecDot(m, q, &dot), "VecDot");
      check(VecAXPY(m, -dot, q), "VecAXPY");
    }
    PetscReal norm = 0.0;
    check(VecNormalize(m, &norm), "VecNormalize");
    if (norm > 0.0)
      kept.push_back(m);
    else
      check(VecDestroy(&m), "VecDestroy");
  }
  modes = kept;
}

void set_near_null_space(Mat A, const std::vector<double>& coordinates) {
  MPI_Comm comm;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(A), &comm), "PetscObjectGetComm");
  PetscInt local_rows = 0, dofs = 1;
  check(MatGetLocalSize(A, &local_rows, nullptr), "MatGetLocalSize");
  check(MatGetBlockSize(A, &dofs), "MatGetBlockSize");
  MF_REQUIRE(static_cast<PetscInt>(coordinates.size()) == local_rows,
             "multigrid: ", static_cast<int>(dofs), " coordinates per owned node are needed (",
             static_cast<long>(local_rows), " in all here), not ", coordinates.size());
  std::vector<Vec> modes = rigid_body_modes(comm, coordinates, dofs);
  zero_held_rows(modes, penalty_held_rows(A));
  MatNullSpace near;
  check(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(modes.size()), modes.data(),
                           &near),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(A, near), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&near), "MatNullSpaceDestroy");
  for (Vec& m : modes) check(VecDestroy(&m), "VecDestroy");
}

namespace {

/// Stagnation: the residual norm the KSP tests has not fallen below kStagnationFactor times
/// the smallest value it had kStagnationWindow iterations earlier. A solve that gains less than
/// a factor 2 in 200 iterations needs over 8,000 to gain the 1e12 of its default tolerance, far
/// past its limit of 2,000, so stopping it early loses nothing.
constexpr int kStagnationWindow = 200;
constexpr double kStagnationFactor = 0.5;

using ConvergenceTest = PetscErrorCode (*)(KSP, PetscInt, PetscReal, KSPConvergedReason*, void*);

/// PETSc's default convergence test, the smallest residual so far at each iteration, and the
/// solve's progress lines (rank 0): the share done is the decades of the residual reduced, of
/// those the relative tolerance asks for.
struct StagnationTest {
  void* default_context = nullptr;
  std::vector<PetscReal> best;
  bool stagnated = false;
  int longest = 0;    // the most iterations of a solve since take_longest_solve
  bool large = false; // a system of log::kProgressUnknowns or more: every tenth and 100%
  int rank = 0;
  std::unique_ptr<log::PhaseProgress> progress;
};

/// The share of a solve done when its residual has fallen from `initial` to `now` and must
/// fall by the relative tolerance rtol.
double solve_fraction(PetscReal initial, PetscReal now, PetscReal rtol) {
  if (!(initial > 0.0) || !(now > 0.0) || !(rtol > 0.0) || rtol >= 1.0) return 0.0;
  return std::clamp(std::log(now / initial) / std::log(rtol), 0.0, 1.0);
}

/// ", iteration 40, residual 1.23e-05 of its initial value" for a progress line.
std::string iteration_detail(const StagnationTest& t, PetscInt it, PetscReal rnorm) {
  char text[96];
  const PetscReal initial = t.best.front();
  std::snprintf(text, sizeof text, ", iteration %d, residual %.3g of its initial value",
                static_cast<int>(it), initial > 0.0 ? rnorm / initial : rnorm);
  return text;
}

void track_progress(StagnationTest& t, KSP ksp, PetscInt it, PetscReal rnorm,
                    KSPConvergedReason reason) {
  if (it == 0)
    t.progress = std::make_unique<log::PhaseProgress>("linear solve", 1.0, t.rank == 0, nullptr,
                                                      nullptr, t.large);
  if (!t.progress) return;
  PetscReal rtol = 0.0;
  if (KSPGetTolerances(ksp, &rtol, nullptr, nullptr, nullptr) != 0) return;
  if (reason > 0)
    t.progress->finish();
  else if (reason == KSP_CONVERGED_ITERATING)
    t.progress->update(solve_fraction(t.best.front(), rnorm, rtol), iteration_detail(t, it, rnorm));
}

PetscErrorCode stagnation_test(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason,
                               void* ctx) {
  auto& t = *static_cast<StagnationTest*>(ctx);
  const PetscErrorCode ierr = KSPConvergedDefault(ksp, it, rnorm, reason, t.default_context);
  if (ierr) return ierr;
  if (it == 0) {
    t.best.clear();
    t.stagnated = false;
  }
  // best[k]: the smallest residual up to iteration k (a KSP may test an iteration twice).
  const auto k = static_cast<std::size_t>(it);
  t.best.resize(k + 1, t.best.empty() ? rnorm : t.best.back());
  t.best[k] = std::min(t.best[k], rnorm);
  t.longest = std::max(t.longest, static_cast<int>(it));
  track_progress(t, ksp, it, rnorm, *reason);
  if (*reason == KSP_CONVERGED_ITERATING && k >= kStagnationWindow &&
      !(t.best[k] < kStagnationFactor * t.best[k - kStagnationWindow])) {
    t.stagnated = true;
    *reason = KSP_DIVERGED_ITS;
  }
  return 0;
}

PetscErrorCode destroy_stagnation_test(void* ctx) {
  auto* t = static_cast<StagnationTest*>(ctx);
  const PetscErrorCode ierr = KSPConvergedDefaultDestroy(t->default_context);
  delete t;
  return ierr;
}

/// Installs the stagnation test and the progress lines on ksp (the test wraps PETSc's default,
/// so every -ksp_ tolerance still applies; -ksp_convergence_test replaces it).
void watch_iterations(KSP ksp, Mat A) {
  MPI_Comm comm;
  check(PetscObjectGetComm(reinterpret_cast<PetscObject>(ksp), &comm), "PetscObjectGetComm");
  auto* t = new StagnationTest;
  MPI_Comm_rank(comm, &t->rank);
  PetscInt rows = 0;
  check(MatGetSize(A, &rows, nullptr), "MatGetSize");
  t->large = static_cast<double>(rows) >= log::kProgressUnknowns;
  check(KSPConvergedDefaultCreate(&t->default_context), "KSPConvergedDefaultCreate");
  check(KSPSetConvergenceTest(ksp, stagnation_test, t, destroy_stagnation_test),
        "KSPSetConvergenceTest");
}

void set_multigrid_solver(KSP ksp, Mat A, const LinearSolverSettings& settings) {
  set_near_null_space(A, settings.coordinates);
  check(KSPSetType(ksp, settings.symmetric ? KSPCG : KSPGMRES), "KSPSetType");
  // Convergence on the preconditioned residual: the multigrid's inverse turns the residual's
  // forces into displacements, in which the penalty rows (alpha ~ 1e6 E / h) no longer
  // outweigh the rest. On the true residual, 1e-10 of |b| left the reactions of a displacement-
  // driven strip 6e-4 off the direct solve's; on the preconditioned one, 1e-12 gives 4e-9.
  check(KSPSetNormType(ksp, KSP_NORM_PRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(ksp, settings.relative_tolerance, 0.0, PETSC_DEFAULT, 2000),
        "KSPSetTolerances");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  set_penalty_band_multigrid(pc, settings.fine_smoother == LinearSolverSettings::FineSmoother::sor);
  // The Chebyshev smoothers aim at [0.05, 1.5] times the estimated largest eigenvalue of their
  // level (PETSc's default [0.1, 1.1]): on the strip's plastic tangents at 10^5 DOFs the
  // estimate fell short, the smoother amplified the stiffest modes and CG stopped with an
  // indefinite preconditioner after 8 cut-backs; with the wider bound all 46 Newton iterations
  // converge (85 CG iterations per solve, results equal to MUMPS's to 2e-7), at 27-28 instead
  // of 26 iterations on the plate.
  default_option("mg_levels_ksp_chebyshev_esteig", "0,0.05,0,1.5");
  // Three Chebyshev steps per level instead of two: the plastic tangents of the perforated
  // strip, where the yielded band is soft in one direction, took 42-47 CG iterations per solve
  // with two and 33-37 with three; the plate takes 20 instead of 26 in about the same time.
  default_option("mg_levels_ksp_max_it", "3");
}

} // namespace

void set_default_solver(KSP ksp, Mat A, const LinearSolverSettings& settings) {
  watch_iterations(ksp, A);
  if (settings.multigrid)
    set_multigrid_solver(ksp, A, settings);
  else
    set_direct_solver(ksp, settings.symmetric);
}

std::string stagnation_note(KSP ksp) {
  ConvergenceTest test = nullptr;
  void* ctx = nullptr;
  PetscErrorCode (*destroy)(void*) = nullptr;
  check(KSPGetConvergenceTest(ksp, &test, &ctx, &destroy), "KSPGetConvergenceTest");
  if (test != stagnation_test || !static_cast<StagnationTest*>(ctx)->stagnated) return "";
  const auto& best = static_cast<StagnationTest*>(ctx)->best;
  char note[200];
  std::snprintf(note, sizeof note,
                "the residual stagnated (it fell by less than a factor %g over the last %d "
                "iterations; the smallest was %.3e of its initial value)",
                1.0 / kStagnationFactor, kStagnationWindow,
                best.front() > 0.0 ? best.back() / best.front() : best.back());
  return note;
}

int take_longest_solve(KSP ksp) {
  ConvergenceTest test = nullptr;
  void* ctx = nullptr;
  PetscErrorCode (*destroy)(void*) = nullptr;
  check(KSPGetConvergenceTest(ksp, &test, &ctx, &destroy), "KSPGetConvergenceTest");
  if (test != stagnation_test) return -1;
  auto& t = *static_cast<StagnationTest*>(ctx);
  const int most = t.longest;
  t.longest = 0;
  return most;
}

std::set<std::string>& options_set_by_code() {
  static std::set<std::string> names;
  return names;
}

std::vector<double> gather(Vec x, bool everywhere) {
  VecScatter scatter;
  Vec all;
  check(everywhere ? VecScatterCreateToAll(x, &scatter, &all)
                   : VecScatterCreateToZero(x, &scatter, &all),
        "VecScatterCreate");
  check(VecScatterBegin(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  PetscInt n;
  check(VecGetLocalSize(all, &n), "VecGetLocalSize");
  const PetscScalar* a;
  check(VecGetArrayRead(all, &a), "VecGetArrayRead");
  std::vector<double> out(a, a + n);
  check(VecRestoreArrayRead(all, &a), "VecRestoreArrayRead");
  VecScatterDestroy(&scatter);
  VecDestroy(&all);
  return out;
}

SolveReport solve_report(KSP ksp) {
  SolveReport r;
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  PetscInt its = 0;
  check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
  r.iterations = static_cast<int>(its);
  r.converged_reason = static_cast<int>(reason);
  r.reason_name = KSPConvergedReasons[reason];
  r.solver = describe(ksp);
  return r;
}

std::string describe(KSP ksp) {
  KSPType kt;
  PCType pt;
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(KSPGetType(ksp, &kt), "KSPGetType");
  check(PCGetType(pc, &pt), "PCGetType");
  std::string s = std::string(kt) + "/" + pt;
  const char* name = nullptr;
  if (std::string(pt) == PCSHELL && PCShellGetName(pc, &name) == 0 && name)
    s = std::string(kt) + "/" + name;
  MatSolverType st = nullptr;
  if (PCFactorGetMatSolverType(pc, &st) == 0 && st) s += "/" + std::string(st);
  return s;
}

} // namespace mf::solvers::detail
