#pragma once
// Particle lattices: the cell centres of a box divided into equal cells (peridynamic and SPH
// bodies, filtered by the caller with the body's shape, holes and notches), and concentric rings
// of points filling an annulus.
#include "meshfree/core/types.hpp"
#include <algorithm>
#include <cmath>

namespace mf::geometry {

/// count[d] cells of size step(d) from lo along each of the first `dims` axes; one layer at 0
/// along the others.
struct Lattice {
  Vec3 lo{0, 0, 0}, step{0, 0, 0};
  long count[3] = {1, 1, 1};

  /// Cells of exactly `spacing`, as many as fit [lo, hi] when rounded (at least one per axis).
  static Lattice of_spacing(const Vec3& lo, const Vec3& hi, double spacing, int dims) {
    Lattice l = cells(lo, hi, spacing, dims);
    for (int d = 0; d < dims; ++d) l.step(d) = spacing;
    return l;
  }
  /// As many cells as `spacing` gives when rounded, stretched to fill [lo, hi] exactly.
  static Lattice fitted(const Vec3& lo, const Vec3& hi, double spacing, int dims) {
    Lattice l = cells(lo, hi, spacing, dims);
    for (int d = 0; d < dims; ++d) l.step(d) = (hi(d) - lo(d)) / l.count[d];
    return l;
  }
  double cells_total() const { return static_cast<double>(count[0]) * count[1] * count[2]; }
  /// The cell size to the power of the dimension (1 times each used axis' step).
  double cell_volume(int dims) const {
    double v = 1.0;
    for (int d = 0; d < dims; ++d) v *= step(d);
    return v;
  }
  Vec3 centre(long i, long j, long k) const {
    return {lo.x() + (i + 0.5) * step.x(), lo.y() + (j + 0.5) * step.y(),
            lo.z() + (k + 0.5) * step.z()};
  }
  /// f(centre) for every cell, x fastest, then y, then z.
  template <class F> void for_each(F&& f) const {
    for (long k = 0; k < count[2]; ++k)
      for (long j = 0; j < count[1]; ++j)
        for (long i = 0; i < count[0]; ++i) f(centre(i, j, k));
  }

private:
  static Lattice cells(const Vec3& lo, const Vec3& hi, double spacing, int dims) {
    Lattice l;
    for (int d = 0; d < dims; ++d) l.lo(d) = lo(d);
    for (int d = 0; d < dims; ++d)
      l.count[d] = std::max(1L, static_cast<long>(std::lround((hi(d) - lo(d)) / spacing)));
    return l;
  }
};

/// Points on concentric circles about `centre` (in the x-y plane) filling the annulus between
/// `inner` and `outer`: round((outer - inner) / spacing) rings at mid-layer radii r_k, each with
/// round(2 pi r_k / spacing) points (at least 3) whose areas add up to the annulus exactly.
/// f(point, area) for each.
template <class F>
void for_each_ring_point(const Vec3& centre, double inner, double outer, double spacing, F&& f) {
  const double thickness = outer - inner;
  const int layers = std::max(1, static_cast<int>(std::lround(thickness / spacing)));
  const double dr = thickness / layers;
  for (int k = 0; k < layers; ++k) {
    const double r = inner + (k + 0.5) * dr;
    const int around = std::max(3, static_cast<int>(std::lround(2.0 * M_PI * r / spacing)));
    for (int a = 0; a < around; ++a) {
      const double theta = 2.0 * M_PI * (a + 0.5) / around;
      f(Vec3(centre.x() + r * std::cos(theta), centre.y() + r * std::sin(theta), 0.0),
        2.0 * M_PI * r * dr / around);
    }
  }
}

} // namespace mf::geometry
