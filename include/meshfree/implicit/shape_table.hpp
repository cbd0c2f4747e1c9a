#pragma once
// Shape functions and gradients at a list of points, in compressed rows: one layout for plane
// (dim 2) and solid (dim 3) bodies, meshfree or finite elements.
#include "meshfree/core/types.hpp"
#include <vector>

namespace mf::implicit {

template <int dim> struct ShapeTableOf {
  using Gradient = Eigen::Matrix<double, dim, 1>;
  std::vector<int> offset{0};
  std::vector<int> node;
  std::vector<double> phi;
  std::vector<Gradient> dphi;
  /// The test functions' gradients where they differ from the trial ones (the variationally
  /// consistent correction, implicit/integration_correction); empty otherwise.
  std::vector<Gradient> test_dphi;
  /// With the volumetric strain of a cell's mean (implicit/volumetric_projection): each entry's
  /// cell mean of the gradient less its own, for the trial and (where they differ) the test
  /// functions; empty otherwise. The strain matrix becomes B + m (mean g - g)^T / dim, m the
  /// unit normal strains of the dim directions.
  std::vector<Gradient> volumetric_shift, test_volumetric_shift;

  int rows() const { return static_cast<int>(offset.size()) - 1; }
  /// Test-function gradients of row r's nodes.
  const Gradient* test_gradients(int r) const {
    return (test_dphi.empty() ? dphi.data() : test_dphi.data()) + offset[r];
  }
  /// The shifts of row r (null without the projection).
  const Gradient* trial_shifts(int r) const {
    return volumetric_shift.empty() ? nullptr : volumetric_shift.data() + offset[r];
  }
  const Gradient* test_shifts(int r) const {
    if (volumetric_shift.empty()) return nullptr;
    return (test_volumetric_shift.empty() ? volumetric_shift.data()
                                          : test_volumetric_shift.data()) +
           offset[r];
  }
};

using ShapeTable = ShapeTableOf<2>;
using SolidShapeTable = ShapeTableOf<3>;

} // namespace mf::implicit
