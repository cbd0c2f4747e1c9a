#pragma once
// Exact sparsity of a meshfree Galerkin matrix: nodes I and J couple when some integration
// point lies in both supports.
#include "meshfree/implicit/meshfree_space.hpp"
#include <vector>

namespace mf::implicit {

/// For each node in [begin, end), how many distinct nodes it couples to inside and outside
/// [begin, end) (itself included), over the support lists of every point in `lists`.
void coupling_counts(const std::vector<const Csr*>& lists, int node_count, int begin, int end,
                     std::vector<int>& inside, std::vector<int>& outside);

} // namespace mf::implicit
