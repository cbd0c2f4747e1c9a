#pragma once
// What `meshfree check` says of a Galerkin run before it starts: the method, its nodes or mesh,
// integration points and memory, the boundary conditions and the steps (the nodes, points and
// mesh built as the run builds them).
#include "meshfree/spec/problem_spec.hpp"
#include <ostream>
#include <string>

namespace mf::implicit {

/// A plane body's plan, or a 3D body's (print_solid_plan).
void print_galerkin_plan(const spec::ProblemSpec& spec, std::ostream& os);
/// The nodes a Galerkin body will have at its base spacing (a lattice over its bounding box, in
/// layers along z for a 3D body), before they are made.
double estimated_nodes(const spec::ProblemSpec& spec);
/// An elastoplastic schedule's increments bounded by the time a run may take here and by the disk
/// of `folder`; the step whose increments pass a bound is named.
void require_increment_output(const spec::ProblemSpec& spec, const std::string& folder);

} // namespace mf::implicit
