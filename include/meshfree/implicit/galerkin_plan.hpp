#pragma once
// What `meshfree check` says of a Galerkin run before it starts: the method, its nodes or mesh,
// integration points and memory, the boundary conditions and the steps (the nodes, points and
// mesh built as the run builds them).
#include "meshfree/spec/problem_spec.hpp"
#include <ostream>

namespace mf::implicit {

void print_galerkin_plan(const spec::ProblemSpec& spec, std::ostream& os);

} // namespace mf::implicit
