#pragma once
// Pairs of points whose distance is below the sum of their own radii, for clouds whose radii
// differ from point to point (SPH with smoothing lengths that follow the density). One cell grid
// over all points needs cells of the largest reach, so a small point would examine every point
// within the largest reach. Here the points are split into classes of radius, factors of two
// ([r_min 2^c, r_min 2^(c+1))), each class binned into its own grid with cells of its own largest
// pair reach, and a point examines in each class only the cells its reach to that class overlaps:
// a multi-level grid, the role trees play for variable h (Hernquist & Katz 1989, TREESPH). Within
// one class it is the linked-cell search (Hockney & Eastwood 1988) with cells of the kernel
// support, as compared for SPH by Dominguez, Crespo, Gomez-Gesteira & Marongiu 2011
// ("Neighbour lists in smoothed particle hydrodynamics", Int. J. Numer. Meth. Fluids 67).
#include "meshfree/neighbors/pair_list.hpp"
#include <vector>

namespace mf::neighbors {

/// Rows i = 0 .. rows-1 of the pairs (i, j), j != i any point (those at index >= rows, such as
/// ghosts, included), with
///   r2 < ((radius_i + radius_j) scale)^2,  r2 = sum_d (x[3i+d] - x[3j+d])^2 summed over d = 0,1,2
/// (this exact expression, so a caller's own test of a pair agrees bit for bit); each row sorted
/// increasingly. Points are x[3i .. 3i+2] (z = 0 in a plane), radius.size() = x.size() / 3,
/// every radius > 0. OpenMP-parallel over rows; the result does not depend on the thread count.
/// Rows of points at index >= rows are left out: offset has rows + 1 entries.
PairList pairs_within_reach(const std::vector<double>& x, const std::vector<double>& radius,
                            double scale, int rows);

} // namespace mf::neighbors
