#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/progress.hpp"
#include "petsc_detail.hpp"
#include <algorithm>
#include <chrono>
#include <petscksp.h>
#include <string>

namespace mf::solvers {

using detail::check;

namespace detail {
namespace {
std::string& petsc_error_text() {
  static std::string text;
  return text;
}

/// Keeps the first message of an error (where it was raised) and prints nothing: the caller's
/// check() turns it into one line, where PETSc's default handler printed a 12-line traceback.
PetscErrorCode keep_message(MPI_Comm, int, const char*, const char*, PetscErrorCode n,
                            PetscErrorType p, const char* message, void*) {
  if (p == PETSC_ERROR_INITIAL) {
    std::string text = message ? message : "";
    std::replace_if(text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    petsc_error_text() = text;
  }
  return n;
}
} // namespace

std::string last_petsc_error() {
  return petsc_error_text();
}
} // namespace detail

PetscSession::PetscSession(int* argc, char*** argv) {
  check(PetscInitialize(argc, argv, nullptr, nullptr), "PetscInitialize");
  PetscPushErrorHandler(detail::keep_message, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  log::rank() = rank_;
}

PetscSession::PetscSession(MPI_Comm comm) : comm_(comm), finalises_(false) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

std::unique_ptr<const PetscSession> PetscSession::this_rank_alone() {
  return std::unique_ptr<const PetscSession>(new PetscSession(MPI_COMM_SELF));
}

PetscSession::~PetscSession() {
  if (finalises_) PetscFinalize();
}

void PetscSession::collective(const std::function<void()>& work) const {
  std::string message;
  try {
    work();
  } catch (const CollectiveError&) {
    throw;
  } catch (const std::exception& e) {
    message = e.what();
  }
  int mine = message.empty() ? size_ : rank_, first = size_;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm_);
  if (first == size_) return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm_);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm_);
  throw CollectiveError(size_ > 1 ? message + " (on rank " + std::to_string(first) + ")" : message);
}

std::vector<std::string> PetscSession::unused_options() const {
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  check(PetscOptionsLeftGet(nullptr, &count, &names, &values), "PetscOptionsLeftGet");
  std::vector<std::string> left;
  for (PetscInt k = 0; k < count; ++k)
    if (!detail::options_set_by_code().count(names[k]))
      left.push_back("-" + std::string(names[k]) +
                     (values[k] ? " " + std::string(values[k]) : std::string()));
  check(PetscOptionsLeftRestore(nullptr, &count, &names, &values), "PetscOptionsLeftRestore");
  return left;
}

OwnedRange owned_nodes(int n, int rank, int size) {
  const int base = n / size, extra = n % size;
  const int begin = rank * base + std::min(rank, extra);
  return {begin, begin + base + (rank < extra ? 1 : 0)};
}

int owner_of(int node, int n, int size) {
  const int base = n / size, extra = n % size;
  const int cut = extra * (base + 1); // first `extra` ranks own base + 1 nodes
  return node < cut ? node / (base + 1) : extra + (node - cut) / std::max(base, 1);
}

struct BlockLinearSystem::Impl {
  Mat A = nullptr;
  Vec b = nullptr, x = nullptr;
  KSP ksp = nullptr;
  LinearSolverSettings settings;
};

BlockLinearSystem::BlockLinearSystem(MPI_Comm comm, int node_count, OwnedRange owned,
                                     const std::vector<int>& row_offset,
                                     const std::vector<int>& columns, const BlockFill& fill,
                                     bool spd, const LinearSolverSettings& settings, int dofs)
    : impl_(std::make_unique<Impl>()) {
  impl_->settings = settings;
  impl_->settings.symmetric = spd && settings.symmetric;
  impl_->A = detail::create_block_matrix(comm, node_count, owned, row_offset, columns, dofs);
  const std::size_t owned_dofs = dofs * static_cast<std::size_t>(owned.end - owned.begin);
  std::vector<double> rhs(owned_dofs, 0.0);
  detail::write_block_values(impl_->A, [&](BlockValueArrays values) { fill(values, rhs); });
  MF_REQUIRE(rhs.size() == owned_dofs, "BlockLinearSystem: inconsistent right-hand side");
  if (impl_->settings.symmetric)
    check(MatSetOption(impl_->A, MAT_SPD, PETSC_TRUE), "MatSetOption(MAT_SPD)");
  check(MatCreateVecs(impl_->A, &impl_->x, &impl_->b), "MatCreateVecs");
  PetscScalar* bv;
  check(VecGetArray(impl_->b, &bv), "VecGetArray");
  std::copy(rhs.begin(), rhs.end(), bv);
  check(VecRestoreArray(impl_->b, &bv), "VecRestoreArray");
}

BlockLinearSystem::~BlockLinearSystem() {
  if (impl_->ksp) KSPDestroy(&impl_->ksp);
  if (impl_->A) MatDestroy(&impl_->A);
  if (impl_->b) VecDestroy(&impl_->b);
  if (impl_->x) VecDestroy(&impl_->x);
}

SolveReport BlockLinearSystem::solve(const std::vector<double>& rhs) {
  Impl& s = *impl_;
  PetscInt local = 0;
  check(VecGetLocalSize(s.b, &local), "VecGetLocalSize");
  MF_REQUIRE(rhs.size() == static_cast<std::size_t>(local),
             "BlockLinearSystem: a right-hand side of ", rhs.size(), " values for ", local,
             " owned rows");
  PetscScalar* bv;
  check(VecGetArray(s.b, &bv), "VecGetArray");
  std::copy(rhs.begin(), rhs.end(), bv);
  check(VecRestoreArray(s.b, &bv), "VecRestoreArray");
  return solve();
}

std::vector<double> BlockLinearSystem::solution() const {
  const PetscScalar* xv;
  PetscInt local = 0;
  check(VecGetLocalSize(impl_->x, &local), "VecGetLocalSize");
  check(VecGetArrayRead(impl_->x, &xv), "VecGetArrayRead");
  std::vector<double> out(xv, xv + local);
  check(VecRestoreArrayRead(impl_->x, &xv), "VecRestoreArrayRead");
  return out;
}

namespace {

/// Sets up ksp's preconditioner (the multigrid hierarchy or the factorisation), with a line
/// before and after it for systems of log::kProgressUnknowns or more: it has no progress of its
/// own to report and takes tens of seconds there.
void set_up_reported(KSP ksp, Mat A) {
  PetscInt rows = 0;
  check(MatGetSize(A, &rows, nullptr), "MatGetSize");
  if (static_cast<double>(rows) < log::kProgressUnknowns) return; // KSPSolve sets it up
  log::info("linear solve: setting up the preconditioner (", detail::describe(ksp), ")");
  const auto start = std::chrono::steady_clock::now();
  check(KSPSetUp(ksp), "KSPSetUp");
  log::info("linear solve: preconditioner set up, elapsed ",
            log::duration(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
}

} // namespace

SolveReport BlockLinearSystem::solve() {
  Impl& s = *impl_;
  // The solver is set up once: a later solve with another right-hand side reuses its
  // factorisation or multigrid hierarchy.
  if (!s.ksp) {
    MPI_Comm comm;
    check(PetscObjectGetComm(reinterpret_cast<PetscObject>(s.A), &comm), "PetscObjectGetComm");
    check(KSPCreate(comm, &s.ksp), "KSPCreate");
    check(KSPSetOperators(s.ksp, s.A, s.A), "KSPSetOperators");
    detail::set_default_solver(s.ksp, s.A, s.settings);
    check(KSPSetFromOptions(s.ksp), "KSPSetFromOptions");
    set_up_reported(s.ksp, s.A);
  }
  PC pc;
  check(KSPGetPC(s.ksp, &pc), "KSPGetPC");
  check(KSPSolve(s.ksp, s.b, s.x), "KSPSolve");

  SolveReport r = detail::solve_report(s.ksp);
  // True residual |b - A x| / |b|, whatever the KSP reports.
  Vec res;
  check(VecDuplicate(s.b, &res), "VecDuplicate");
  check(MatMult(s.A, s.x, res), "MatMult");
  check(VecAYPX(res, -1.0, s.b), "VecAYPX");
  PetscReal rn = 0.0, bn = 0.0;
  check(VecNorm(res, NORM_2, &rn), "VecNorm");
  check(VecNorm(s.b, NORM_2, &bn), "VecNorm");
  check(VecDestroy(&res), "VecDestroy");
  r.residual_norm = bn > 0.0 ? rn / bn : rn;
  if (r.converged_reason <= 0) {
    PCFailedReason pcr = PC_NOERROR;
    PCGetFailedReasonRank(pc, &pcr);
    const std::string stalled = detail::stagnation_note(s.ksp);
    fail("linear solve failed: ",
         stalled.empty() ? "KSP stopped with " + r.reason_name : "stopped: " + stalled, " after ",
         r.iterations, " iterations (solver ", r.solver, ", preconditioner: ", PCFailedReasons[pcr],
         "); ",
         s.settings.multigrid ? detail::kMultigridHint
                              : "a factorisation that fails usually means the body is not held "
                                "against rigid motion");
  }
  // The reason alone does not say the system was solved: a KSP of type preonly reports
  // CONVERGED_ITS after one application of whatever preconditioner it was given (with
  // -pc_type none, x = b). The true residual decides: a direct solve, backward stable, leaves
  // round-off; an iterative one meets its relative tolerance on its own norm (by default the
  // preconditioned residual), which the true residual may exceed by the preconditioner's
  // conditioning (gmres/ilu on plate_tension: 166 times), hence the wide factor; but never above
  // 1e-3, whatever -ksp_rtol says: a looser solve (-ksp_rtol 0.5 left 0.47) is no solution.
  KSPType type;
  check(KSPGetType(s.ksp, &type), "KSPGetType");
  PetscReal rtol = 0.0, abstol = 0.0, dtol = 0.0;
  PetscInt maxits = 0;
  check(KSPGetTolerances(s.ksp, &rtol, &abstol, &dtol, &maxits), "KSPGetTolerances");
  const bool direct = std::string(type) == KSPPREONLY;
  const double limit = direct ? 1e-6 : std::clamp(1000.0 * static_cast<double>(rtol), 1e-6, 1e-3);
  if (!(r.residual_norm <= limit))
    fail("linear solve did not solve the system: relative residual |b - A x| / |b| = ",
         r.residual_norm, " (accepted up to ", limit, ") although KSP reported ", r.reason_name,
         " (solver ", r.solver,
         "); check the PETSc options given after -- (an iterative solver: a smaller -ksp_rtol, or "
         "-ksp_norm_type unpreconditioned)");
  return r;
}

std::vector<double> BlockLinearSystem::solution_everywhere() const {
  return detail::gather(impl_->x, /*everywhere=*/true);
}

double BlockLinearSystem::global_nonzeros() const {
  MatInfo info;
  check(MatGetInfo(impl_->A, MAT_GLOBAL_SUM, &info), "MatGetInfo");
  return info.nz_used;
}

} // namespace mf::solvers
