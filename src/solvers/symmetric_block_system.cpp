#include "meshfree/solvers/symmetric_block_system.hpp"
#include "petsc_detail.hpp"
#include <chrono>
#include <petscksp.h>
#include <string>

namespace mf::solvers {

using detail::check;

namespace {

/// The upper triangle in scalar compressed rows: scalar rows 2i and 2i + 1 of block row i.
struct UpperRows {
  std::vector<PetscInt> offset{0}, column;
  std::vector<double> value;
};

/// Scalar row 2i + r of block row i: the diagonal block's entries on or right of the diagonal,
/// then row r of each off-diagonal block.
void append_scalar_row(const UpperBlockRows& K, int i, int r, UpperRows& S) {
  for (int t = K.offset[i]; t < K.offset[i + 1]; ++t) {
    const double* b = &K.value[4 * static_cast<std::size_t>(t)];
    for (int col = t == K.offset[i] ? r : 0; col < 2; ++col) {
      S.column.push_back(2 * K.column[t] + col);
      S.value.push_back(b[2 * r + col]);
    }
  }
  S.offset.push_back(static_cast<PetscInt>(S.column.size()));
}

UpperRows scalar_rows(const UpperBlockRows& K) {
  const int n = K.nodes();
  UpperRows S;
  S.offset.reserve(2 * static_cast<std::size_t>(n) + 1);
  S.column.reserve(4 * K.column.size());
  S.value.reserve(4 * K.column.size());
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < 2; ++r) append_scalar_row(K, i, r, S);
  return S;
}

} // namespace

struct SymmetricBlockSystem::Impl {
  UpperRows rows;
  std::string prefix;
  int size = 0;
  Mat A = nullptr;
  Vec b = nullptr, x = nullptr;
  KSP ksp = nullptr;
  double factorisation_seconds = 0.0;
};

SymmetricBlockSystem::SymmetricBlockSystem(const UpperBlockRows& rows,
                                           const std::string& options_prefix)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.prefix = options_prefix;
  MF_REQUIRE(rows.column.size() == static_cast<std::size_t>(rows.offset.back()) &&
                 rows.value.size() == 4 * rows.column.size(),
             "symmetric block system: inconsistent block rows");
  s.rows = scalar_rows(rows);
  s.size = 2 * rows.nodes();
  // The symmetric format (SBAIJ) holds the upper triangle alone, in these very arrays; block
  // size 1, which every Cholesky package PETSc offers takes.
  check(MatCreateSeqSBAIJWithArrays(PETSC_COMM_SELF, 1, s.size, s.size, s.rows.offset.data(),
                                    s.rows.column.data(), s.rows.value.data(), &s.A),
        "MatCreateSeqSBAIJWithArrays");
  check(MatSetOption(s.A, MAT_SPD, PETSC_TRUE), "MatSetOption(MAT_SPD)");
  check(MatCreateVecs(s.A, &s.x, &s.b), "MatCreateVecs");
}

SymmetricBlockSystem::~SymmetricBlockSystem() {
  if (impl_->ksp) KSPDestroy(&impl_->ksp);
  if (impl_->A) MatDestroy(&impl_->A);
  if (impl_->b) VecDestroy(&impl_->b);
  if (impl_->x) VecDestroy(&impl_->x);
}

namespace {

/// A direct solve by MUMPS's sparse Cholesky, options under the prefix (pd_:
/// -pd_pc_factor_mat_solver_type cholmod) overriding it. A direct solve because its
/// factorisation, made once, serves every Newton step: measured on peridynamic bodies (README),
/// MUMPS factorises as fast as CHOLMOD's supernodal Cholesky or faster, and conjugate gradients
/// with incomplete Cholesky, whose iterations grow with the body, took three times as long.
KSP cholesky_solver(Mat A, const std::string& prefix) {
  KSP ksp;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  check(KSPSetOptionsPrefix(ksp, prefix.c_str()), "KSPSetOptionsPrefix");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  return ksp;
}

} // namespace

SolveReport SymmetricBlockSystem::solve(const std::vector<double>& rhs) {
  Impl& s = *impl_;
  MF_REQUIRE(rhs.size() == static_cast<std::size_t>(s.size),
             "symmetric block system: a right-hand side of ", rhs.size(), " values for ",
             s.size, " rows");
  if (!s.ksp) {
    const auto start = std::chrono::steady_clock::now();
    s.ksp = cholesky_solver(s.A, s.prefix);
    check(KSPSetUp(s.ksp), "KSPSetUp");
    s.factorisation_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  PetscScalar* bv;
  check(VecGetArray(s.b, &bv), "VecGetArray");
  std::copy(rhs.begin(), rhs.end(), bv);
  check(VecRestoreArray(s.b, &bv), "VecRestoreArray");
  check(KSPSolve(s.ksp, s.b, s.x), "KSPSolve");
  SolveReport r = detail::solve_report(s.ksp);
  if (r.converged_reason <= 0) {
    PC pc;
    check(KSPGetPC(s.ksp, &pc), "KSPGetPC");
    PCFailedReason failed = PC_NOERROR;
    PCGetFailedReasonRank(pc, &failed);
    fail("linear solve failed: KSP stopped with ", r.reason_name, " (solver ", r.solver,
         ", preconditioner: ", PCFailedReasons[failed], ")");
  }
  return r;
}

std::vector<double> SymmetricBlockSystem::solution() const {
  const PetscScalar* xv;
  check(VecGetArrayRead(impl_->x, &xv), "VecGetArrayRead");
  std::vector<double> out(xv, xv + impl_->size);
  check(VecRestoreArrayRead(impl_->x, &xv), "VecRestoreArrayRead");
  return out;
}

double SymmetricBlockSystem::factorisation_seconds() const {
  return impl_->factorisation_seconds;
}

} // namespace mf::solvers
