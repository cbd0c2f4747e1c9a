#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/core/error.hpp"
#include "petsc_detail.hpp"
#include <algorithm>
#include <cmath>
#include <petscsnes.h>

namespace mf::solvers {

using detail::check;

struct NonlinearBlockSystem::Impl {
  MPI_Comm comm;
  int node_count = 0;
  int dofs = 2; // per node
  OwnedRange owned;
  ResidualFunction residual;
  JacobianFunction jacobian;

  SNES snes = nullptr;
  Mat J = nullptr;
  Vec x = nullptr, r = nullptr;
  Vec ghost = nullptr;               // sequential: the needed entries
  VecScatter pull = nullptr;         // x -> ghost
  std::vector<PetscInt> ghost_index; // global DOF of each ghost entry

  std::vector<double> d;      // full-length iterate seen by the callbacks
  double scale = 0.0;         // force scale of the last residual evaluation
  double floor = 0.0;         // round-off floor of |R| at the last residual evaluation
  bool floor_reached = false; // the previous iterate of this solve was within its floor
  double tolerance = 1e-8;
  int max_iterations = 20;
  double keep_tangent = 0.0; // NewtonSettings::keep_tangent of the solve under way
  bool new_tangent = true;   // the next Jacobian evaluation builds one (J holds none yet)
  bool kept_last = false;    // the last iteration's correction came from a kept tangent
  bool multigrid = false;    // the default linear solver is multigrid (for the failure's hint)
  std::vector<double> coordinates; // the owned nodes' positions, for multigrid's near-null space
  NewtonReport report;

  /// Copies the owned and needed entries of X into d.
  void pull_values(Vec X) {
    check(VecScatterBegin(pull, X, ghost, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(pull, X, ghost, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* g;
    check(VecGetArrayRead(ghost, &g), "VecGetArrayRead");
    for (std::size_t k = 0; k < ghost_index.size(); ++k) d[ghost_index[k]] = g[k];
    check(VecRestoreArrayRead(ghost, &g), "VecRestoreArrayRead");
  }

  /// Records a failure on this rank; returns true if any rank failed (collective).
  bool any_failed(const std::string& message) {
    int mine = message.empty() ? 0 : 1, any = 0;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
    if (mine && report.failure.empty()) report.failure = message;
    if (any && report.failure.empty()) report.failure = "an evaluation failed on another rank";
    return any != 0;
  }
};

namespace {

PetscErrorCode form_function(SNES snes, Vec X, Vec F, void* ctx) {
  auto& s = *static_cast<NonlinearBlockSystem::Impl*>(ctx);
  s.pull_values(X);
  PetscScalar* f;
  PetscCall(VecGetArray(F, &f));
  ResidualSums mine;
  std::string failure;
  try {
    s.residual(s.d, f, mine);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  PetscCall(VecRestoreArray(F, &f));
  double sums[2] = {mine.scale_squared, mine.floor_squared};
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, s.comm);
  s.scale = std::sqrt(sums[0]);
  s.floor = std::sqrt(sums[1]);
  if (s.any_failed(failure)) PetscCall(SNESSetFunctionDomainError(snes));
  return 0;
}

PetscErrorCode form_jacobian(SNES snes, Vec X, Mat, Mat P, void* ctx) {
  auto& s = *static_cast<NonlinearBlockSystem::Impl*>(ctx);
  // A kept tangent: P is left as it is, so PETSc sees an unchanged operator and keeps its
  // factors (PCSetUp does nothing for an operator whose state has not changed).
  s.kept_last = s.keep_tangent > 0.0 && !s.new_tangent;
  if (s.kept_last) return 0;
  ++s.report.tangents;
  s.pull_values(X);
  std::string failure;
  try {
    check(MatZeroEntries(P), "MatZeroEntries"); // the callback adds to zeros
    detail::write_block_values(P, [&](BlockValueArrays values) { s.jacobian(s.d, values); });
    if (s.multigrid) detail::set_near_null_space(P, s.coordinates);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  const bool failed = s.any_failed(failure);
  if (failed) PetscCall(SNESSetJacobianDomainError(snes));
  s.new_tangent = failed; // a tangent that failed is not kept
  return 0;
}

/// Force-based test: |R| <= tolerance * |F| (the residual callback reports |F|). SNES's default
/// test compares with |R| at the start of the step, which under displacement control through
/// penalty terms is dominated by alpha * (jump of the prescribed value) and says nothing about
/// equilibrium. Penalty terms also put a floor under |R|: a penalty row is the difference of
/// K_pen d and alpha times the prescribed value, both near alpha u, so it is known only to
/// round-off of that size (near 1e-8 |F| with alpha = 1e6 E/h on a plate at its limit load,
/// growing with the prescribed displacement). The residual reports that floor (eps times the
/// magnitudes of each row's terms, [Higham 2002] ch. 3). Two iterates in a row within it are as
/// converged as the arithmetic can tell: the second is a full Newton iteration from the floor.
/// One is not enough: near a limit load the tangent is nearly singular, and the first iterate
/// to reach the floor may still differ from the next by a correction along the soft mode.
/// The Newton corrections that round-off produces there need not be small next to d either, so
/// the step alone cannot say when to stop; the older stagnation rule stays for the other
/// cases: a correction below 1e-8 of d (SNES's own step tolerance) with |R| within 1e3 of the
/// tolerance, from a new tangent only (a kept tangent's corrections shrink with |R| but only
/// linearly, so a small one says nothing of how close equilibrium is).
PetscErrorCode converged(SNES, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm,
                         SNESConvergedReason* reason, void* ctx) {
  auto& s = *static_cast<NonlinearBlockSystem::Impl*>(ctx);
  // Modified Newton: a new tangent after an iteration that contracted |R| too little (fnorm is
  // the same on every rank, so all decide alike).
  if (it > 0 && fnorm > s.keep_tangent * s.report.residual.back()) s.new_tangent = true;
  s.report.residual.push_back(fnorm);
  s.report.scale.push_back(s.scale);
  *reason = SNES_CONVERGED_ITERATING;
  const bool within_floor = fnorm <= s.floor;
  const bool floor_twice = it > 0 && within_floor && s.floor_reached;
  s.floor_reached = within_floor;
  if (!std::isfinite(fnorm))
    *reason = SNES_DIVERGED_FNORM_NAN;
  else if (fnorm <= s.tolerance * s.scale || floor_twice)
    *reason = SNES_CONVERGED_FNORM_ABS;
  else if (it > 0 && !s.kept_last && snorm <= 1e-8 * xnorm && fnorm <= 1e3 * s.tolerance * s.scale)
    *reason = SNES_CONVERGED_SNORM_RELATIVE;
  else if (it >= s.max_iterations)
    *reason = SNES_DIVERGED_MAX_IT;
  return 0;
}

} // namespace

NonlinearBlockSystem::NonlinearBlockSystem(MPI_Comm comm, int node_count, OwnedRange owned,
                                           const std::vector<int>& row_offset,
                                           const std::vector<int>& columns,
                                           const std::vector<int>& needed,
                                           ResidualFunction residual, JacobianFunction jacobian,
                                           const LinearSolverSettings& linear, int dofs)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.comm = comm;
  s.node_count = node_count;
  s.dofs = dofs;
  s.owned = owned;
  s.residual = std::move(residual);
  s.jacobian = std::move(jacobian);
  s.d.assign(dofs * static_cast<std::size_t>(node_count), 0.0);

  s.J = detail::create_block_matrix(comm, node_count, owned, row_offset, columns, dofs);
  // The consistent tangent of associative plasticity plus the penalty terms is symmetric (in a
  // Galerkin form, not with corrected test functions).
  if (linear.symmetric)
    check(MatSetOption(s.J, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption(MAT_SYMMETRIC)");
  check(MatCreateVecs(s.J, &s.x, &s.r), "MatCreateVecs");

  // The entries the callbacks read: owned nodes and the needed ones, without repeats.
  std::vector<char> mark(node_count, 0);
  for (int I = owned.begin; I < owned.end; ++I) mark[I] = 1;
  for (int I : needed) {
    MF_REQUIRE(I >= 0 && I < node_count, "NonlinearBlockSystem: needed node out of range");
    mark[I] = 1;
  }
  for (int I = 0; I < node_count; ++I)
    if (mark[I])
      for (int c = 0; c < dofs; ++c) s.ghost_index.push_back(dofs * static_cast<PetscInt>(I) + c);
  IS is;
  check(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(s.ghost_index.size()),
                        s.ghost_index.data(), PETSC_COPY_VALUES, &is),
        "ISCreateGeneral");
  check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(s.ghost_index.size()), &s.ghost),
        "VecCreateSeq");
  check(VecScatterCreate(s.x, is, s.ghost, nullptr, &s.pull), "VecScatterCreate");
  check(ISDestroy(&is), "ISDestroy");

  check(SNESCreate(comm, &s.snes), "SNESCreate");
  check(SNESSetType(s.snes, SNESNEWTONLS), "SNESSetType");
  check(SNESSetFunction(s.snes, s.r, form_function, &s), "SNESSetFunction");
  check(SNESSetJacobian(s.snes, s.J, s.J, form_jacobian, &s), "SNESSetJacobian");
  check(SNESSetConvergenceTest(s.snes, converged, &s, nullptr), "SNESSetConvergenceTest");
  // Backward-Euler J2 makes each increment the stationarity condition of an incremental
  // potential, so the critical-point line search fits: it seeks a zero of the directional
  // derivative along the Newton step. The default backtracking (bt) demands a decrease of |R|
  // at every step and rejects the non-monotone but convergent full steps of Newton in a
  // perfectly plastic plateau (plate_plastic_limit: bt stops after 8 cut-backs, cp completes).
  SNESLineSearch ls;
  check(SNESGetLineSearch(s.snes, &ls), "SNESGetLineSearch");
  check(SNESLineSearchSetType(ls, SNESLINESEARCHCP), "SNESLineSearchSetType");
  KSP ksp;
  check(SNESGetKSP(s.snes, &ksp), "SNESGetKSP");
  detail::set_default_solver(ksp, s.J, linear);
  s.multigrid = linear.multigrid;
  s.coordinates = linear.coordinates;
  check(SNESSetFromOptions(s.snes), "SNESSetFromOptions");
}

NonlinearBlockSystem::~NonlinearBlockSystem() {
  Impl& s = *impl_;
  if (s.snes) SNESDestroy(&s.snes);
  if (s.pull) VecScatterDestroy(&s.pull);
  if (s.ghost) VecDestroy(&s.ghost);
  if (s.J) MatDestroy(&s.J);
  if (s.x) VecDestroy(&s.x);
  if (s.r) VecDestroy(&s.r);
}

namespace {

/// Why SNES stopped, with what the linear solver says of a failed linear solve.
std::string stop_reason(NonlinearBlockSystem::Impl& s, KSP ksp, SNESConvergedReason reason) {
  std::string why = SNESConvergedReasons[reason];
  const std::string stalled =
      reason == SNES_DIVERGED_LINEAR_SOLVE ? detail::stagnation_note(ksp) : "";
  if (!stalled.empty()) why += " (linear solve stopped: " + stalled + ")";
  if (reason == SNES_DIVERGED_LINEAR_SOLVE && s.multigrid) {
    why += std::string(" (") + detail::kMultigridHint + ")";
  } else if (reason == SNES_DIVERGED_LINEAR_SOLVE) {
    PC pc;
    check(KSPGetPC(ksp, &pc), "KSPGetPC");
    PCFailedReason pcr = PC_NOERROR;
    PCGetFailedReasonRank(pc, &pcr);
    int code = static_cast<int>(pcr);
    MPI_Allreduce(MPI_IN_PLACE, &code, 1, MPI_INT, MPI_MAX, s.comm);
    if (code != PC_NOERROR)
      why += std::string(" (") + PCFailedReasons[code] +
             (code == PC_FACTOR_NUMERIC_ZEROPIVOT || code == PC_FACTOR_OTHER
                  ? ": the tangent is singular, as at a limit load under load control)"
                  : ")");
  }
  return why;
}

/// Sets the line search's record of the last step's length to zero. SNES keeps it from the
/// previous solve, and the critical-point line search compares the first step's dot(F, Y) with
/// atol times it: after a solve that diverged to an infinite step, the next one would stop at its
/// start as converged.
void forget_last_step(SNES snes) {
  SNESLineSearch ls;
  check(SNESGetLineSearch(snes, &ls), "SNESGetLineSearch");
  PetscReal xnorm, fnorm, ynorm;
  check(SNESLineSearchGetNorms(ls, &xnorm, &fnorm, &ynorm), "SNESLineSearchGetNorms");
  check(SNESLineSearchSetNorms(ls, xnorm, fnorm, 0.0), "SNESLineSearchSetNorms");
}

/// One SNES solve from the owned entries of d, with s.keep_tangent as set.
NewtonReport attempt(NonlinearBlockSystem::Impl& s, const std::vector<double>& d) {
  if (s.keep_tangent <= 0.0) s.new_tangent = true;
  s.report = NewtonReport{};
  PetscScalar* xv;
  check(VecGetArray(s.x, &xv), "VecGetArray");
  std::copy(d.begin() + s.dofs * s.owned.begin, d.begin() + s.dofs * s.owned.end, xv);
  check(VecRestoreArray(s.x, &xv), "VecRestoreArray");

  KSP ksp;
  check(SNESGetKSP(s.snes, &ksp), "SNESGetKSP");
  detail::take_longest_solve(ksp);
  forget_last_step(s.snes);
  check(SNESSolve(s.snes, nullptr, s.x), "SNESSolve");
  s.report.linear_iterations_max = detail::take_longest_solve(ksp);

  SNESConvergedReason reason;
  check(SNESGetConvergedReason(s.snes, &reason), "SNESGetConvergedReason");
  // The critical-point line search ends a solve as converged by itself where dot(F, Y) is below
  // atol |Y|. Every stop of converged() lies within the stagnation rule's bound, so a converged
  // solve beyond it is such a stop: taken within the bound (a step from the penalty rows'
  // round-off floor: |R| about 2e-7 |F| on beam_voce_bending's first increments), not beyond.
  const bool unaccepted =
      reason > 0 && !(s.report.residual.back() <= std::max(s.floor, 1e3 * s.tolerance * s.scale));
  if (unaccepted) reason = SNES_DIVERGED_LINE_SEARCH;
  if (reason <= 0) s.new_tangent = true; // the next solve starts from a tangent of its own
  PetscInt its = 0, lits = 0;
  check(SNESGetIterationNumber(s.snes, &its), "SNESGetIterationNumber");
  check(SNESGetLinearSolveIterations(s.snes, &lits), "SNESGetLinearSolveIterations");
  s.report.converged = reason > 0;
  s.report.iterations = static_cast<int>(its);
  s.report.linear_iterations = static_cast<int>(lits);
  s.report.reason = stop_reason(s, ksp, reason);
  if (unaccepted)
    s.report.reason =
        mf::detail::concat("the line search stopped at |R| = ", s.report.residual.back(),
                           " with |F| = ", s.report.scale.back(), ", far above the tolerance");
  return s.report;
}

} // namespace

NewtonReport NonlinearBlockSystem::solve(std::vector<double>& d, const NewtonSettings& settings) {
  Impl& s = *impl_;
  MF_REQUIRE(d.size() == s.d.size(), "NonlinearBlockSystem::solve: wrong vector length");
  s.tolerance = settings.tolerance;
  s.max_iterations = settings.max_iterations;
  // Maximum iterations as a SNES setting too, so that SNES itself stops there.
  check(SNESSetTolerances(s.snes, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT,
                          settings.max_iterations, PETSC_DEFAULT),
        "SNESSetTolerances");
  s.keep_tangent = settings.keep_tangent;
  NewtonReport rep = attempt(s, d);
  // Kept tangents that did not reach equilibrium (their iterations contract |R| linearly, and
  // a perfectly plastic plateau can use up the iterations allowed): the same start again with
  // Newton's method, before the caller cuts the increment back.
  if (!rep.converged && rep.tangents < rep.iterations) { // some iteration kept a tangent
    s.keep_tangent = 0.0;
    const NewtonReport kept = rep;
    rep = attempt(s, d);
    rep.iterations += kept.iterations;
    rep.linear_iterations += kept.linear_iterations;
    rep.linear_iterations_max = std::max(rep.linear_iterations_max, kept.linear_iterations_max);
    rep.tangents += kept.tangents;
  }
  s.pull_values(s.x);
  for (std::size_t k = 0; k < s.ghost_index.size(); ++k)
    d[s.ghost_index[k]] = s.d[s.ghost_index[k]];
  return rep;
}

std::vector<double> NonlinearBlockSystem::gather_on_root(const std::vector<double>& d) const {
  const Impl& s = *impl_;
  Vec local;
  check(VecDuplicate(s.x, &local), "VecDuplicate");
  PetscScalar* lv;
  check(VecGetArray(local, &lv), "VecGetArray");
  MF_REQUIRE(d.size() == s.d.size(), "NonlinearBlockSystem::gather_on_root: wrong vector length");
  std::copy(d.begin() + s.dofs * s.owned.begin, d.begin() + s.dofs * s.owned.end, lv);
  check(VecRestoreArray(local, &lv), "VecRestoreArray");
  std::vector<double> out = detail::gather(local, /*everywhere=*/false);
  VecDestroy(&local);
  return out;
}

std::string NonlinearBlockSystem::description() const {
  SNESType st;
  check(SNESGetType(impl_->snes, &st), "SNESGetType");
  std::string out = st;
  SNESLineSearch ls;
  if (SNESGetLineSearch(impl_->snes, &ls) == 0) {
    SNESLineSearchType lt;
    if (SNESLineSearchGetType(ls, &lt) == 0 && lt) out += "(" + std::string(lt) + ")";
  }
  KSP ksp;
  check(SNESGetKSP(impl_->snes, &ksp), "SNESGetKSP");
  return out + " + " + detail::describe(ksp);
}

} // namespace mf::solvers
