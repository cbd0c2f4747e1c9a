#pragma once
// What the LPS passes (pd/state_based.hpp) read and write, shared by their scalar rows
// (state_based.cpp) and their packed rows (state_rows_packed.cpp).
#include "meshfree/core/simd_target.hpp"
#include "meshfree/pd/model.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::pd::detail {

inline constexpr double kNone = -std::numeric_limits<double>::infinity();

/// What both passes read: positions, rows, per-class influence and the particles' constants.
struct Family {
  const double* y; // three a point
  const long* offset;
  const int* partner;
  ClassView cls;
  const BondClass* classes;
  const double* omega; // per class
  unsigned char* intact;
  int owned;
  bool half;
  bool aware;                 // position-aware factors (pd/state_surface.hpp) in the classes
  double d;                   // dimensions
  const double* y4 = nullptr; // the positions four a point (x, y, z, 0) for the packed rows
};

/// One bond seen from its row's particle at (xi, yi, zi): y_j - y_i, its length r and its
/// extension e = r - |xi|.
struct Stretch {
  double dx, dy, dz, r, e;
};

inline Stretch stretch_of(const Family& f, int j, const BondClass& c, double xi, double yi,
                          double zi) {
  const double dx = f.y[3 * j] - xi, dy = f.y[3 * j + 1] - yi, dz = f.y[3 * j + 2] - zi;
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  return {dx, dy, dz, r, r - c.length};
}

/// What pass 2 reads per particle: t_i = omega (iso_i |xi| + scale_i b_i (e^d - e^dp)) with
/// iso_i = d kappa theta_i / m_i, b_i = a mu / m_i, e^d = e - theta_i |xi| / d; the plastic
/// return's factor scale_i (1 without plasticity); theta_i and kappa_i for the energy; the
/// committed s0 of the LAMMPS rule; the bonds' plastic deviatoric extensions (two a stored bond:
/// the row particle's, then the partner's), null for an elastic body.
struct StateTerms {
  const double* iso;
  const double* b;
  const double* theta;
  const double* kappa; // per particle, for the energy
  const double* s0;    // null without the alpha rule
  bool energy;
  bool breaking;       // false: every bond intact at the start stays intact
  const double* scale; // null: 1
  double* plastic;     // null: elastic
  /// The packed rows': four a particle, theta / d, iso, b and 0, so that a partner's three are
  /// one load (null for the scalar rows).
  const double* partner = nullptr;
};

/// One end's deviatoric state of a bond of extension e: its elastic deviatoric extension
/// e^d - e^dp before the return.
inline double elastic_deviatoric(double e, double theta_over_d, double length,
                                 const double* plastic, long slot) {
  return e - theta_over_d * length - (plastic ? plastic[slot] : 0.0);
}

/// Where pass 2 writes: forces (3 a point), energy density, trial s0, element 0 at `base`.
struct PassOut {
  double* f;
  double* w;
  double* s0n;
  int base;
};

inline double critical(const BondClass& c, const double* s0, double s0_i, int j) {
  return s0 ? std::max(std::min(s0_i, s0[j]), c.alpha_floor) : c.limit;
}

/// The packed rows (x86-64, AVX2; the same numbers as the scalar rows bit for bit) of pass 1,
/// the dilatation's sums of an LPS body (not position-aware), and of pass 2, the forces of an
/// elastic one, over rows [lo, hi): as dilatation_rows and force_rows<kAware> of
/// state_based.cpp, reading the positions from f.y4. Pass 2 is for elastic bodies (t.plastic
/// and t.scale null).
void packed_dilatation_rows(const Family& f, int lo, int hi, double* theta, double* other,
                            int base);
long packed_force_rows(const Family& f, const StateTerms& t, int lo, int hi, const PassOut& out);

/// Whether the packed rows are compiled here and chosen (core/simd_target.hpp).
inline bool packed_rows() {
#if defined(__x86_64__) && defined(__GNUC__)
  return simd_target() != SimdTarget::Baseline;
#else
  return false;
#endif
}

} // namespace mf::pd::detail
