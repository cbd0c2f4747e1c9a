#pragma once
// Symmetric 3x3 tensors in Voigt order (xx yy zz yz xz xy) in closed form: their eigenvalues by the
// trigonometric solution of the characteristic cubic [Smith 1961], and their positive part, the
// sum over the positive eigenvalues of lambda v v^T, with an eigenvector of a simple eigenvalue as
// the largest cross product of two rows of (A - lambda I) [Kopp 2008] and its eigenvalue as the
// Rayleigh quotient. The tensor is scaled by its largest entry first, so that no power of an
// entry under- or overflows. A few dozen flops where an iterative solver (Eigen's
// SelfAdjointEigenSolver) takes some hundreds: what SPH's artificial stress asks of every
// particle at every stage. Measured against Eigen's solver (tests/unit/core/test_symmetric3.cpp):
// the positive part within 2.4e-15 of the largest eigenvalue, the eigenvalues within 2.2e-14,
// and within 5e-10 where two of them nearly coincide (the trigonometric form's sqrt(eps)).
#include <array>

namespace mf {

/// The eigenvalues of a, largest first.
std::array<double, 3> symmetric_eigenvalues(const double a[6]);

/// The positive part of a: a's eigenvalues below zero set to zero, its eigenvectors kept
/// (out = a where no eigenvalue is negative, 0 where none is positive).
void positive_part(const double a[6], double out[6]);

} // namespace mf
