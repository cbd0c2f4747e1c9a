#pragma once
// Static equilibrium of a peridynamic body under held loads, reached two ways:
//  - adaptive dynamic relaxation (ADR; Kilic & Madenci 2010; Madenci & Oterkus 2014, the
//    adaptive dynamic relaxation of their numerical solution chapter): a fictitious diagonal
//    density that makes the central-difference iteration stable at a unit step, and a damping
//    coefficient renewed every iteration from the lowest frequency of the body as a Rayleigh
//    quotient of a local stiffness estimate;
//  - explicit dynamic relaxation as LS-DYNA does it: the physical density and a stable step,
//    the loads ramped and then held, mass-proportional damping, stopped when the kinetic energy
//    has fallen to a fraction of its peak.
// Both use the bond-force loop of pd/forces.hpp, and the loads as pd::Loading gives them: body
// loads and prescribed displacements at the body's current time (their time functions are not
// followed; the explicit relaxation multiplies them by its own ramp). Components under a velocity
// constraint stay where they are.
#include "meshfree/pd/dynamics.hpp"
#include <string>
#include <vector>

namespace mf::pd {

struct RelaxSettings {
  /// Converged when |residual force| <= tolerance * |external force|: 2-norms of the forces
  /// (force density times volume) over the free components; the external force is the larger of
  /// the body loads on the free components and the reactions on the held ones.
  double tolerance = 1e-6;
  int max_iterations = 100000;
  bool allow_breaking = false; // else bonds do not break (and the LAMMPS s0 is left as it is)
  /// solve_statics: the linear solver of the Newton steps; automatic takes multigrid from
  /// kMultigridFromParticles particles up and the Cholesky factorisation below.
  enum class LinearSolver { automatic, cholesky, multigrid };
  LinearSolver linear_solver = LinearSolver::automatic;
};

/// The body size (particles) from which solve_statics solves by multigrid rather than by a
/// factorisation (see README, the implicit peridynamic equilibrium).
inline constexpr int kMultigridFromParticles = 5000;

struct RelaxReport {
  int iterations = 0;
  bool converged = false;
  double residual_ratio = 0.0; // |residual| / |external| at the end
  double seconds = 0.0;
  int linear_iterations = 0;     // solve_statics: the linear solver's, over all Newton iterations
  std::string solver;            // solve_statics: the linear solver
  double assembly_seconds = 0.0; // solve_statics: making the stiffness matrix
  double factorisation_seconds = 0.0; // solve_statics: its factorisation or multigrid set-up
};

/// Brings the body from its current u to static equilibrium under the loading (body loads at
/// their factor at the body's current time, held and prescribed displacements), bonds unbroken
/// unless allowed, by adaptive dynamic relaxation; leaves v = 0, a = 0 and the clock as it was.
/// Micro-plastic bonds yield along the relaxation's fictitious path.
RelaxReport relax(Model& m, BondState& s, const Loading& loading, const RelaxSettings& settings);

/// Brings a plane body from its current u to static equilibrium under the loading by Newton's
/// method with the linearised bond stiffness at the reference directions, K_ij = -V_i c w_ij /
/// |xi| e e^T and K_ii = -sum_j K_ij over the intact bonds (the tangent of the bond force at
/// u = 0; Peridigm's QuasiStatic solver is Newton on the same equations): its upper triangle
/// assembled in one pass over the bonds and reused at every iteration: a modified Newton whose
/// residual falls by about the strain per iteration. Below kMultigridFromParticles it is
/// factorised once by a sparse Cholesky (solvers::SymmetricBlockSystem, MUMPS); from there up
/// (or when settings.linear_solver or -pd_pc_type gamg asks) each step is solved by conjugate
/// gradients with GAMG and the rigid-body near-null space (solvers::MultigridBlockSystem), as
/// accurately as the tolerance still asks. PETSc options prefixed pd_ override either solver.
/// Held components keep their targets (their rows and columns are the identity). A diagonal
/// shift of 1e-8 of each free diagonal entry makes the matrix of a body held by forces alone
/// positive definite, and the rigid motions the held components leave free are taken out of
/// every right-hand side and step. The residual, evaluated by the bond-force loop, decides
/// convergence as in relax; nothing is assembled when the body starts in equilibrium. Every
/// particle must be owned (one rank); bonds do not break. Leaves v = 0, a = 0 and the clock as
/// it was. A state-based (elastic LPS) body takes Newton-Krylov steps instead: conjugate
/// gradients on its own tangent, applied by central differences of its forces (two force
/// evaluations an iteration), preconditioned by the bond stiffness above with the body's contact
/// micromodulus (the bond-based body of its bulk modulus), each step as accurate as the
/// tolerance asks; an eps body relaxes by ADR.
RelaxReport solve_statics(Model& m, BondState& s, const Loading& loading,
                          const RelaxSettings& settings);

struct ExplicitRelaxSettings {
  double dt = 0.0;        // time step (the physical density is used): at most stable_time_step
  double ramp_time = 0.0; // loads and prescribed displacements rise linearly over it, then held
  double damping = 0.0;   // c of the mass-proportional damping a -= c v (1/time)
  double ke_ratio = 1e-3; // stop when, after the ramp, kinetic energy <= ke_ratio * its peak
  double residual_tolerance = 0.0; // also stop when, after the ramp, the residual ratio <= it
  long max_steps = 10000000;
  bool allow_breaking = false;
};

struct ExplicitRelaxReport {
  long steps = 0;
  bool converged = false;      // a stopping criterion was met within max_steps
  double time = 0.0;           // physical time simulated
  double peak_kinetic = 0.0;   // the peak of the kinetic energy
  double kinetic_ratio = 0.0;  // kinetic energy / peak at the end
  double residual_ratio = 0.0; // as RelaxReport's, at the end under the full loads
  double seconds = 0.0;
};

/// Explicit dynamic relaxation from the body's current u: velocity Verlet with damping (the
/// second half kick implicit in the damping term), loads ramped over ramp_time and then held,
/// until the kinetic energy criterion (or the residual one) is met. Leaves v = 0, a = 0 and the
/// clock (time, step) as it was, as LS-DYNA resets it after dynamic relaxation.
ExplicitRelaxReport explicit_relax(Model& m, BondState& s, const Loading& loading,
                                   const ExplicitRelaxSettings& settings);

/// Puts the displacement u (3 per particle) on every particle, at rest (v = 0, a = 0). Bonds keep
/// their reference lengths, intact flags and plastic stretches: the stretches of the next force
/// evaluation follow from X + u.
void set_displacement(Model& m, const std::vector<double>& u);

/// The residual ratio |residual| / |external| of the body as it stands (see RelaxSettings).
/// Breaks no bond.
double residual_ratio(Model& m, BondState& s, const Loading& loading);

} // namespace mf::pd
