#pragma once
// The volumetric strain of a 3D body projected onto the constants of each background cell or
// element: the B-bar method (Hughes 1980; for reproducing-kernel approximations, Chen et al.
// 2000). Every Gauss point of a cell takes the cell's mean volumetric strain and keeps its own
// deviatoric strain,
//   eps_bar = eps + m (theta_mean - theta) / 3,  theta_mean = sum_g w_g theta_g / sum_g w_g,
// m = [1 1 1 0 0 0], so a cell carries one incompressibility constraint instead of one per Gauss
// point and isochoric plastic flow does not lock. A linear displacement field has theta_mean =
// theta, and a constant stress's mean pressure does no work on the shifts (they sum to zero over
// a cell): the patch test holds as without the projection. The map d -> eps_bar is linear, so
// the consistent tangent B_bar^T C B_bar keeps Newton's rate.
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/solid_space.hpp"
#include <vector>

namespace mf::implicit {

/// Each point's support widened to the union of the supports of its cell's points (`cell`, per
/// point), sorted: every row of a cell then lists the same nodes, and the nodes of the cell's
/// mean strain.
Csr cell_supports(const Csr& support, const std::vector<int>& cell);

/// Sets the table's volumetric shifts (SolidShapeTable::volumetric_shift): at each row of a
/// cell, the mean over the cell's rows (weights `weight`) of each node's gradient less the
/// row's own, for the trial functions and for the test functions where they differ. The rows of
/// a cell must list the same nodes (cell_supports) and all be in the table (`cell`, per row).
void project_volumetric_strain(SolidShapeTable& t, const std::vector<int>& cell,
                               const std::vector<double>& weight);

} // namespace mf::implicit
