#pragma once
// The readers the plane and the 3D Galerkin analyses share: the body's material, the
// discretisation, the linear solver, the load steps and the Newton controls.
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

/// The body's material: the one `material:` names, or the single entry; it needs E and nu.
/// Returns its index into p.materials.
int take_material(KeyReader& r, const ProblemSpec& p, const std::string& analysis);
/// linear_solver: {type: auto | direct | multigrid, multigrid_above}.
LinearSolverSpec read_linear_solver(KeyReader& r);
/// discretisation: method, spacing, refinement boxes, shape functions (of dimension `dim`) and
/// quadrature; the node counts of the plane body within `bounds` checked against the memory.
DiscretisationSpec read_discretisation(KeyReader& r, int dim, const BoundingBox& bounds,
                                       const std::string& base_dir,
                                       const LinearSolverSpec& solver = {});
/// Bytes per Galerkin node at a run's peak with the linear solver that `count` nodes get.
double bytes_per_node(const LinearSolverSpec& solver, double count);
/// discretisation.adapt: {target, fraction, passes, max_nodes, pilot_increments}, refused for a
/// body of dimension other than 2 or for finite elements; max_nodes checked against the memory.
std::optional<AdaptSpec> read_adapt(KeyReader& d, int dim, const DiscretisationSpec& s,
                                    const LinearSolverSpec& solver);
/// steps: [{name, increments, load_factor, factors: {condition: target}}]; `boundary` names the
/// conditions in order (the body force is the last factor).
std::vector<LoadStep> read_steps(KeyReader& r, const std::vector<std::string>& boundary,
                                 bool geostatic);
/// nonlinear: {tolerance, max_iterations, max_cutbacks}.
NonlinearSpec read_nonlinear(KeyReader& r);

} // namespace mf::spec
