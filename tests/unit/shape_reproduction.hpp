#pragma once
// The check every node-cloud test makes of its shape functions: evaluated at points of the body
// (every point has them: shape_table throws where one has not), they reproduce 1 and x; and the
// outline tests' whole check of a body's cloud.
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

/// The largest error of the cloud's shape functions in reproducing 1 and x at `points`
/// (linear basis); throws mf::Error naming the first point where they are undefined.
inline double linear_reproduction_error(const mf::implicit::MeshfreeSpace& space,
                                        const std::vector<mf::Vec2>& points) {
  std::vector<int> rows(points.size());
  std::iota(rows.begin(), rows.end(), 0);
  const mf::implicit::ShapeTable t =
      space.shape_table(points, rows, space.support_lists(points), false);
  const std::vector<mf::Vec2>& x = space.nodes().x;
  double worst = 0.0;
  for (int r = 0; r < t.rows(); ++r) {
    double sum = 0.0;
    mf::Vec2 at = mf::Vec2::Zero();
    for (int k = t.offset[r]; k < t.offset[r + 1]; ++k) {
      sum += t.phi[k];
      at += t.phi[k] * x[t.node[k]];
    }
    worst = std::max({worst, std::abs(sum - 1.0), (at - points[r]).norm()});
  }
  return worst;
}

/// A plane body's node cloud at spacing h (no refinement), the way the outline tests check it:
/// how many nodes lie outside the body, and the largest error of the shape functions (linear
/// basis, dilation 2) in reproducing 1 and x at the body's integration points (cells of h, cut
/// two levels).
struct CloudCheck {
  int outside = 0;
  double reproduction = 0.0;
};

inline CloudCheck check_cloud(const mf::geometry::Domain& d, double h) {
  mf::kernels::ShapeSettings shape;
  shape.dim = 2;
  const mf::geometry::NodeCloud cloud = mf::geometry::generate_nodes(d, h, {});
  CloudCheck out;
  for (const mf::Vec2& x : cloud.x) out.outside += d.contains(x, 1e-9) ? 0 : 1;
  const mf::implicit::MeshfreeSpace space(cloud, shape, mf::Vec2(2, 2));
  out.reproduction = linear_reproduction_error(space, mf::quadrature::domain_points(d, h, 3, 2).x);
  return out;
}
