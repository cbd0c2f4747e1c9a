#include "meshfree/solvers/pd_multigrid_system.hpp"
#include "petsc_detail.hpp"
#include <chrono>
#include <cmath>
#include <petscksp.h>
#include <string>

namespace mf::solvers {

using detail::check;

namespace {

/// The whole matrix in scalar compressed rows, columns increasing along each row.
struct FullRows {
  std::vector<PetscInt> offset{0}, column;
  std::vector<double> value;
};

/// The blocks left of the diagonal, by block row in compressed rows: row i's are (i, node[k])
/// for k in offset[i] .. offset[i + 1] - 1, in increasing node, the transposes of the upper
/// triangle's blocks in `slot`.
struct LowerBlocks {
  std::vector<int> offset, slot, node;
};

LowerBlocks lower_blocks(const UpperBlockRows& K) {
  const int n = K.nodes();
  LowerBlocks L;
  L.offset.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int t = K.offset[j] + 1; t < K.offset[j + 1]; ++t) ++L.offset[K.column[t] + 1];
  for (int i = 0; i < n; ++i) L.offset[i + 1] += L.offset[i];
  L.slot.resize(static_cast<std::size_t>(L.offset[n]));
  L.node.resize(L.slot.size());
  std::vector<int> next(L.offset.begin(), L.offset.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int t = K.offset[j] + 1; t < K.offset[j + 1]; ++t) {
      const int k = next[K.column[t]]++;
      L.slot[k] = t;
      L.node[k] = j;
    }
  return L;
}

/// Scalar row 2i + r: the transposed blocks left of the diagonal, then the diagonal block and
/// the blocks right of it, two columns each.
void append_full_row(const UpperBlockRows& K, const LowerBlocks& L, int i, int r, FullRows& S) {
  for (int k = L.offset[i]; k < L.offset[i + 1]; ++k) {
    const double* b = &K.value[4 * static_cast<std::size_t>(L.slot[k])];
    for (int c = 0; c < 2; ++c) {
      S.column.push_back(2 * L.node[k] + c);
      S.value.push_back(b[2 * c + r]);
    }
  }
  for (int t = K.offset[i]; t < K.offset[i + 1]; ++t) {
    const double* b = &K.value[4 * static_cast<std::size_t>(t)];
    for (int c = 0; c < 2; ++c) {
      S.column.push_back(2 * K.column[t] + c);
      S.value.push_back(b[2 * r + c]);
    }
  }
  S.offset.push_back(static_cast<PetscInt>(S.column.size()));
}

FullRows full_rows(const UpperBlockRows& K) {
  const LowerBlocks L = lower_blocks(K);
  FullRows S;
  const std::size_t blocks = 2 * K.column.size() - static_cast<std::size_t>(K.nodes());
  S.offset.reserve(2 * static_cast<std::size_t>(K.nodes()) + 1);
  S.column.reserve(4 * blocks);
  S.value.reserve(4 * blocks);
  for (int i = 0; i < K.nodes(); ++i)
    for (int r = 0; r < 2; ++r) append_full_row(K, L, i, r, S);
  return S;
}

/// The translations and the in-plane rotation about the centroid, zero on the held components,
/// orthonormal (Gram-Schmidt, as MatNullSpaceCreate requires); a mode left with nothing is
/// dropped. Smoothed aggregation interpolates the near-kernel it is given ([Vanek, Mandel &
/// Brezina 1996]); the held components are fixed, so the modes free of energy are zero there.
std::vector<Vec> rigid_modes(const std::vector<double>& x, const std::vector<unsigned char>& held) {
  const std::size_t n = x.size() / 2;
  double centre[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d) centre[d] += x[2 * i + d] / static_cast<double>(n);
  std::vector<Vec> modes(3);
  for (int mode = 0; mode < 3; ++mode) {
    check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(2 * n), &modes[mode]),
          "VecCreateSeq");
    PetscScalar* v;
    check(VecGetArray(modes[mode], &v), "VecGetArray");
    for (std::size_t i = 0; i < n; ++i) {
      const double rotation[2] = {-(x[2 * i + 1] - centre[1]), x[2 * i] - centre[0]};
      for (int d = 0; d < 2; ++d) v[2 * i + d] = mode < 2 ? double(mode == d) : rotation[d];
    }
    check(VecRestoreArray(modes[mode], &v), "VecRestoreArray");
  }
  detail::zero_held_rows(modes, std::vector<char>(held.begin(), held.end()));
  return modes;
}

void set_near_null_space(Mat A, const std::vector<double>& x,
                         const std::vector<unsigned char>& held) {
  std::vector<Vec> modes = rigid_modes(x, held);
  MatNullSpace near;
  check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, static_cast<PetscInt>(modes.size()),
                           modes.data(), &near),
        "MatNullSpaceCreate");
  check(MatSetNearNullSpace(A, near), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&near), "MatNullSpaceDestroy");
  for (Vec& m : modes) check(VecDestroy(&m), "VecDestroy");
}

/// Conjugate gradients with GAMG, the residual measured unpreconditioned so that the tolerance
/// bounds the force left over; options under the prefix override both.
KSP multigrid_solver(Mat A, const std::string& prefix) {
  KSP ksp;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  check(KSPSetOptionsPrefix(ksp, prefix.c_str()), "KSPSetOptionsPrefix");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCGAMG), "PCSetType");
  check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  return ksp;
}

bool option_given(const std::string& prefix, const char* name) {
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, prefix.c_str(), name, &set), "PetscOptionsHasName");
  return set == PETSC_TRUE;
}

} // namespace

struct MultigridBlockSystem::Impl {
  FullRows rows;
  std::string prefix;
  int size = 0;
  Mat A = nullptr;
  Vec b = nullptr, x = nullptr;
  KSP ksp = nullptr;
  double setup_seconds = 0.0;
};

MultigridBlockSystem::MultigridBlockSystem(const UpperBlockRows& rows,
                                           const std::vector<double>& coordinates,
                                           const std::vector<unsigned char>& held,
                                           const std::string& options_prefix)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.prefix = options_prefix;
  s.size = 2 * rows.nodes();
  MF_REQUIRE(rows.column.size() == static_cast<std::size_t>(rows.offset.back()) &&
                 rows.value.size() == 4 * rows.column.size() &&
                 coordinates.size() == static_cast<std::size_t>(s.size) &&
                 held.size() == static_cast<std::size_t>(s.size),
             "multigrid block system: inconsistent block rows, coordinates or held components");
  s.rows = full_rows(rows);
  check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, s.size, s.size, s.rows.offset.data(),
                                  s.rows.column.data(), s.rows.value.data(), &s.A),
        "MatCreateSeqAIJWithArrays");
  check(MatSetBlockSize(s.A, 2), "MatSetBlockSize");
  check(MatSetOption(s.A, MAT_SPD, PETSC_TRUE), "MatSetOption(MAT_SPD)");
  set_near_null_space(s.A, coordinates, held);
  check(MatCreateVecs(s.A, &s.x, &s.b), "MatCreateVecs");
}

MultigridBlockSystem::~MultigridBlockSystem() {
  if (impl_->ksp) KSPDestroy(&impl_->ksp);
  if (impl_->A) MatDestroy(&impl_->A);
  if (impl_->b) VecDestroy(&impl_->b);
  if (impl_->x) VecDestroy(&impl_->x);
}

SolveReport MultigridBlockSystem::solve(const std::vector<double>& rhs, double relative_tolerance) {
  Impl& s = *impl_;
  MF_REQUIRE(rhs.size() == static_cast<std::size_t>(s.size),
             "multigrid block system: a right-hand side of ", rhs.size(), " values for ", s.size,
             " rows");
  if (!s.ksp) {
    const auto start = std::chrono::steady_clock::now();
    s.ksp = multigrid_solver(s.A, s.prefix);
    check(KSPSetUp(s.ksp), "KSPSetUp");
    s.setup_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (!option_given(s.prefix, "-ksp_rtol"))
    check(KSPSetTolerances(s.ksp, relative_tolerance, 0.0, PETSC_DEFAULT, PETSC_DEFAULT),
          "KSPSetTolerances");
  PetscScalar* bv;
  check(VecGetArray(s.b, &bv), "VecGetArray");
  std::copy(rhs.begin(), rhs.end(), bv);
  check(VecRestoreArray(s.b, &bv), "VecRestoreArray");
  check(KSPSolve(s.ksp, s.b, s.x), "KSPSolve");
  SolveReport r = detail::solve_report(s.ksp);
  if (r.converged_reason <= 0)
    fail("linear solve failed: KSP stopped with ", r.reason_name, " after ", r.iterations,
         " iterations (solver ", r.solver, ")");
  return r;
}

std::vector<double> MultigridBlockSystem::solution() const {
  const PetscScalar* xv;
  check(VecGetArrayRead(impl_->x, &xv), "VecGetArrayRead");
  std::vector<double> out(xv, xv + impl_->size);
  check(VecRestoreArrayRead(impl_->x, &xv), "VecRestoreArrayRead");
  return out;
}

double MultigridBlockSystem::setup_seconds() const {
  return impl_->setup_seconds;
}

bool multigrid_asked(const std::string& options_prefix) {
  char type[64] = "";
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, options_prefix.c_str(), "-pc_type", type, sizeof type, &set),
        "PetscOptionsGetString");
  return set == PETSC_TRUE && std::string(type) == PCGAMG;
}

} // namespace mf::solvers
