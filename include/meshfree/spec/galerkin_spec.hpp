#pragma once
// The part of a problem file that belongs to the Galerkin analyses (elastic_static,
// elastoplastic_static, and the 1D model problem): discretisation, boundary conditions, loads,
// load steps, solver controls and output. Plain data.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/kernels/shape_functions.hpp"
#include "meshfree/spec/region_spec.hpp"
#include "meshfree/verification/exact_solutions.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

/// Meshfree Galerkin (RK/MLS nodes on background cells) or finite elements on a mesh; both feed
/// the same assembly, material and solver.
enum class Method { Meshfree, Fem };

/// Finite-element settings (used when the method is fem).
struct FemSpec {
  std::string element = "q8"; // t3 | q4 | q8; model solid_3d: hex8 | hex20 | tet4 | tet10
  std::string mesh;           // gmsh .msh file (absolute path); empty: a structured mesh of the
                              // rectangle with elements of the discretisation's spacing
  int order = 0;              // Gauss points per direction; triangles and tetrahedra: the
                              // degree their rule integrates exactly (0: the element's default)
};

/// A 3D body's brick named by the plane element it extrudes (q4, q8) is the brick (hex8, hex20);
/// plane_element is the way back. Other names are their own.
inline std::string solid_element(const std::string& e) {
  return e == "q4" ? "hex8" : e == "q8" ? "hex20" : e;
}
inline std::string plane_element(const std::string& e) {
  return e == "hex8" ? "q4" : e == "hex20" ? "q8" : e;
}

/// Error-driven refinement of a plane meshfree body's nodes (discretisation.adapt): pilot solves
/// estimate the error (implicit/error_indicator), the nodes carrying the bulk of it get boxes of
/// half their spacing (implicit/adaptivity), and the analysis runs on the last cloud.
struct AdaptSpec {
  double target = 0.02;      // estimated relative energy-norm error at which refinement stops
  double fraction = 0.5;     // Doerfler's bulk: the nodes marked carry this share of eta^2
  int passes = 6;            // pilot solves at most (each may refine the cloud once)
  double max_nodes = 1e5;    // a refinement past this many nodes is not made
  int pilot_increments = 10; // increments of each load step in an elastoplastic pilot
  // Refine during an elastoplastic analysis after every `every` converged increments, the
  // committed state carried to the new cloud, instead of by pilot solves before it (0: pilots).
  int every = 0;
  // With every: estimates (and refinements) in increments 1 to `until` only, the rest of the
  // schedule on the cloud then reached (0: the whole schedule).
  int until = 0;
};

struct DiscretisationSpec {
  Method method = Method::Meshfree;
  FemSpec fem;
  double spacing = 0.0;
  std::vector<geometry::Refinement> refinement;
  kernels::ShapeSettings shape;
  Vec2 dilation{2.0, 2.0}; // support radius = dilation * local spacing
  // Plane meshfree bodies: a node's support ends where the body's boundary hides it (the
  // visibility criterion), so that supports do not reach across a slit, a notch or a thin wall.
  bool visibility = false;
  int order = 3;           // Gauss points per direction in a background cell
  double cell_size = 0.0;  // background cell size (default: spacing)
  int cut_levels = 2;      // subdivisions of cells cut by the boundary
  bool cut_arcs = false;   // cells cut by one hole: exact region (quadrature::cell_minus_disc)
  int boundary_order = 3;  // Gauss points per boundary part
  bool vci = false;        // meshfree: variationally consistent test-function gradients
  // 3D bodies: the volumetric strain at each Gauss point replaced by its mean over the point's
  // background cell or element (B-bar), so that incompressible plastic flow does not lock.
  bool cell_mean_volumetric = false;
  std::optional<AdaptSpec> adapt; // meshfree plane bodies: error-driven refinement
};

struct BoundaryCondition {
  std::string name;
  std::string key_path; // e.g. "boundary[0]", for messages
  Region on;            // named boundary pieces (edges), optionally clipped to a box
  // Displacement (penalty) constraint on the components with mask = 1.
  bool constrains = false;
  Vec2 mask{0.0, 0.0};
  Vec2 value{0.0, 0.0};
  bool value_from_exact = false;
  double penalty = 0.0; // absolute alpha
  // Traction (force per area of the edge face; times thickness gives force per length).
  bool loads = false;
  Vec2 traction{0.0, 0.0};
  bool traction_from_exact = false;
  // Normal pressure (force per area, positive pushing into the body): the traction -p n with n
  // the outward normal of the boundary piece at each point; a load like a traction.
  bool pressure_load = false;
  double pressure = 0.0;
};

/// A region of a Galerkin body made of one entry of the `materials:` list.
struct MaterialRegion {
  int material = 0;     // index into ProblemSpec::materials
  std::string key_path; // e.g. "material_regions[1]", for messages
  Region region;        // box, circle, ring, holes
};

/// The initial stress of a Galerkin body before its first load step (Abaqus *GEOSTATIC, FLAC
/// `initialize-stresses ratio`): at (x, y) the vertical stress is the weight of the column above,
/// sigma_v = -int_y^surface rho(x, z) |g| dz (compression negative), the horizontal and
/// out-of-plane stresses k0 sigma_v (0 out of plane in plane stress), no shear.
struct GeostaticStress {
  double surface = 0.0; // y of the ground surface
  double k0 = 0.5;      // lateral earth pressure coefficient
};

/// A named step of a load schedule: over `increments` equal increments, the factor of every
/// boundary condition (and of the body force, the last entry) moves linearly from its value at the
/// end of the previous step (0 before the first) to `target`. A condition's prescribed
/// displacement or traction is its value times its factor.
struct LoadStep {
  std::string name;
  int increments = 1;
  std::vector<double> target; // per boundary condition, then the body force
};

/// Newton settings and the automatic cut-back of increments that do not converge.
struct NonlinearSpec {
  double tolerance = 1e-8; // |R| <= tolerance * |F|
  int max_iterations = 20;
  int max_cutbacks = 8; // an increment is halved to at most 2^-max_cutbacks of its nominal size
  double keep_tangent = 0.0; // solvers::NewtonSettings::keep_tangent (0: Newton's method)
};

/// The linear solver of the implicit analyses (`linear_solver:`): a direct factorisation below
/// `multigrid_above` DOFs and algebraic multigrid from there (auto), or one of them always.
struct LinearSolverSpec {
  enum class Type { Auto, Direct, Multigrid };
  Type type = Type::Auto;
  double multigrid_above = 2e5; // DOFs
  /// Whether a system of `dofs` unknowns is solved by multigrid.
  bool multigrid_for(double dofs) const {
    return type == Type::Multigrid || (type == Type::Auto && dofs >= multigrid_above);
  }
};

struct LineSpec {
  std::string name;
  Vec2 from{0.0, 0.0}, to{0.0, 0.0};
  int points = 0;
};

/// analysis: model_problem_1d. y'' + f = 0 on [0, L], y(0) = y(L) = 0, with
/// f = A (k pi / L)^2 sin(k pi x / L) + B x; the exact solution is
/// y = A sin(k pi x / L) + B x (L^2 - x^2) / 6. Discretised by 1D meshfree shape functions.
struct ModelProblem1D {
  double length = 1.0;
  double sine_amplitude = 1.0;
  double sine_waves = 1.0;
  double linear = 0.0;
  double penalty = 0.0;
  DiscretisationSpec discretisation;
};

/// analysis: elastic_static or elastoplastic_static. A 2D body discretised by meshfree nodes or
/// finite elements, held and loaded on its boundary, under body forces and an initial stress,
/// loaded in steps (elastoplastic) and solved by Newton's method and a linear solver.
struct GalerkinSpec {
  int material_index = 0; // the body's material in ProblemSpec::materials
  DiscretisationSpec discretisation;
  std::vector<BoundaryCondition> boundary;
  Vec2 body_force{0.0, 0.0}; // force per volume
  // The material of each region (later entries win; points in no region take
  // `material_index`), gravity (acceleration: body force rho g with rho of the point's
  // material; with body_force, scaled by the body-force factor of the steps) and the initial
  // stress.
  std::vector<MaterialRegion> material_regions;
  Vec2 gravity{0.0, 0.0};
  std::optional<GeostaticStress> initial_stress;
  // Keep the nodal parameters of every converged increment (IncrementRecord::parameters), so
  // that a point can be carried through the increments as a passive material point.
  bool record_increment_parameters = false;
  std::optional<verification::ExactSolution> exact;
  std::vector<LineSpec> lines;
  std::vector<GaugeSpec> gauges; // points whose displacement history is recorded
  int fields_every = 1;          // write fields every this many converged increments (and the last)
  // Checkpoints of elastoplastic_static, at converged increments: every `interval` increments
  // (output.checkpoint_every; 0: none by count) and after `wall_interval` seconds of wall time
  // (output.checkpoint_wall_interval).
  CheckpointPolicy checkpoint;
  std::vector<LoadStep> steps;
  NonlinearSpec nonlinear;
  LinearSolverSpec linear_solver;
};

} // namespace mf::spec
