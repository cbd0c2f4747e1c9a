// The bond rows of pd/bond_rows.hpp: the scalar rows (each bond in one pass), and the choice, once
// per call, between them and the packed rows (pd/bond_rows_packed.cpp) for the instruction set
// of core/simd_target.hpp.
#include "meshfree/pd/bond_rows.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__x86_64__) && defined(__GNUC__)
#define MF_PD_X86 1
#else
#define MF_PD_X86 0
#endif

namespace mf::pd {

namespace rows {
namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

/// One bond's scalar force factors. With the stretch s = |y_j - y_i| / |xi| - 1 and the plastic
/// stretch s_p (Macek & Silling 2007: |s - s_p| <= s_Y, the return is exact), the force density
/// on i is c w_ij (s - s_p) (y_j - y_i) / |y_j - y_i| (Silling & Askari 2005, eq. 3 and 6;
/// LAMMPS pair_peri_pmb.cpp, PairPeriPMB::compute, computes dr = r - r0 the same way); the class
/// holds c w_ij and 1 / |xi|, so that the bond costs a square root and one division.
template <bool Plastic> struct Bond {
  double s, e, inv_r; // stretch, elastic stretch s - s_p, 1 / r
  Bond(const BondClass& c, double r2, double* plastic_stretch) {
    const double r = std::sqrt(r2);
    inv_r = r > 0.0 ? 1.0 / r : 0.0;
    s = (r - c.length) * c.inv_length; // r - |xi| is exact near |xi| (Sterbenz)
    e = s;
    if constexpr (Plastic) {
      double sp = *plastic_stretch;
      const double elastic = s - sp;
      if (elastic > c.yield)
        sp = s - c.yield;
      else if (elastic < -c.yield)
        sp = s + c.yield;
      *plastic_stretch = sp;
      e = s - sp;
    }
  }
};

/// Bond k of a row whose particle is at (xi, yi, zi), towards partner j: y_j - y_i and the
/// bond's force factors, as both scalar layouts take them.
template <bool Plastic> struct Stretched {
  double dx, dy, dz;
  Bond<Plastic> bond;
};

template <bool Plastic>
inline Stretched<Plastic> stretched(const Arrays& a, const BondClass& c, long k, int j, double xi,
                                    double yi, double zi) {
  const double dx = a.y[4 * j] - xi, dy = a.y[4 * j + 1] - yi, dz = a.y[4 * j + 2] - zi;
  return {dx, dy, dz,
          Bond<Plastic>(c, dx * dx + dy * dy + dz * dz, Plastic ? &a.plastic[k] : nullptr)};
}

/// The critical stretch of a bond: the law's, or with the LAMMPS rule min(s0_i, s0_j) of the
/// previous evaluation (pair_peri_pmb.cpp, PairPeriPMB::compute) where the law breaks.
template <bool Alpha>
inline double critical(const BondClass& c, const Arrays& a, double s0_i, int j) {
  if constexpr (Alpha)
    return std::max(std::min(s0_i, a.s0[j]), c.alpha_floor);
  else
    return c.limit;
}

/// Half layout, scalar: each stored pair once, the reaction to an owned partner. `cls`: the class
/// indices, two or four bytes (ClassView), a loop for each.
template <bool Plastic, bool Alpha, bool Energy, class Index>
Sums half_rows(const Arrays& a, const Index* cls, int lo, int hi, const Output& out) {
  Sums sums;
  double* const f = out.f;
  for (int i = lo; i < hi; ++i) {
    const double xi = a.y[4 * i], yi = a.y[4 * i + 1], zi = a.y[4 * i + 2];
    const double s0_i = Alpha ? a.s0[i] : 0.0;
    double fx = 0.0, fy = 0.0, fz = 0.0, wi = 0.0, s0_next = kNone;
    for (long k = a.offset[i]; k < a.offset[i + 1]; ++k) {
      if (!a.intact[k]) continue;
      const int j = a.partner[k];
      const BondClass& c = a.classes[cls[k]];
      const auto [dx, dy, dz, bond] = stretched<Plastic>(a, c, k, j, xi, yi, zi);
      const double g = bond.e * bond.inv_r;
      const double gi = c.cw * g, gj = c.cw_partner * g;
      fx += gi * dx, fy += gi * dy, fz += gi * dz;
      const bool j_owned = j < a.owned;
      const std::ptrdiff_t jb = j - out.base;
      if (j_owned) f[4 * jb] -= gj * dx, f[4 * jb + 1] -= gj * dy, f[4 * jb + 2] -= gj * dz;
      if constexpr (Energy) {
        // w = c (s - s_p)^2 |xi| / 2 per bond, half of it to each end.
        const double half_w = 0.25 * bond.e * bond.e * c.length;
        wi += c.cw * half_w;
        if (j_owned) {
          sums.energy += a.volume[j] * c.cw_partner * half_w;
          if (out.w) out.w[jb] += c.cw_partner * half_w;
        }
      }
      if constexpr (Alpha) {
        // LAMMPS: s0 follows the most compressed intact bond, s00 - alpha s.
        const double candidate = c.s00 - c.alpha * bond.s;
        s0_next = std::max(s0_next, candidate);
        if (j_owned) out.s0n[jb] = std::max(out.s0n[jb], candidate);
      }
      if (bond.s > critical<Alpha>(c, a, s0_i, j)) {
        a.intact[k] = 0;
        sums.broken += j_owned ? 2 : 1;
      }
    }
    const std::ptrdiff_t ib = i - out.base;
    f[4 * ib] += fx, f[4 * ib + 1] += fy, f[4 * ib + 2] += fz;
    if constexpr (Energy) {
      sums.energy += a.volume[i] * wi;
      if (out.w) out.w[ib] += wi;
    }
    if constexpr (Alpha) out.s0n[ib] = std::max(out.s0n[ib], s0_next);
  }
  return sums;
}

/// Full layout, scalar: each row its own sums, in the order of its partners.
template <bool Plastic, bool Alpha, bool Energy, class Index>
Sums full_rows(const Arrays& a, const Index* cls, int lo, int hi, const Output& out) {
  Sums sums;
  for (int i = lo; i < hi; ++i) {
    const double xi = a.y[4 * i], yi = a.y[4 * i + 1], zi = a.y[4 * i + 2];
    const double s0_i = Alpha ? a.s0[i] : 0.0;
    double fx = 0.0, fy = 0.0, fz = 0.0, wi = 0.0, s0_next = kNone;
    for (long k = a.offset[i]; k < a.offset[i + 1]; ++k) {
      if (!a.intact[k]) continue;
      const int j = a.partner[k];
      const BondClass& c = a.classes[cls[k]];
      const auto [dx, dy, dz, bond] = stretched<Plastic>(a, c, k, j, xi, yi, zi);
      const double gi = c.cw * bond.e * bond.inv_r;
      fx += gi * dx, fy += gi * dy, fz += gi * dz;
      if constexpr (Energy) wi += c.cw * (0.25 * bond.e * bond.e * c.length);
      if constexpr (Alpha) s0_next = std::max(s0_next, c.s00 - c.alpha * bond.s);
      if (bond.s > critical<Alpha>(c, a, s0_i, j)) {
        a.intact[k] = 0;
        ++sums.broken;
      }
    }
    out.f[3 * i] = fx, out.f[3 * i + 1] = fy, out.f[3 * i + 2] = fz;
    if constexpr (Energy) out.w[i] = wi;
    if constexpr (Alpha) out.s0n[i] = s0_next;
  }
  return sums;
}

using RowsFn = Sums (*)(const Arrays&, int, int, const Output&);

template <bool H, bool P, bool A, bool E>
Sums scalar_rows(const Arrays& a, int lo, int hi, const Output& out) {
  const auto rows = [&](auto cls) {
    return H ? half_rows<P, A, E>(a, cls, lo, hi, out) : full_rows<P, A, E>(a, cls, lo, hi, out);
  };
  return a.cls.narrow ? rows(a.cls.narrow) : rows(a.cls.wide);
}

template <bool H, bool P, bool A> RowsFn of_energy(Terms terms) {
  return terms.energy ? &scalar_rows<H, P, A, true> : &scalar_rows<H, P, A, false>;
}

template <bool H> RowsFn of_terms(Terms terms) {
  if (terms.plastic)
    return terms.alpha ? of_energy<H, true, true>(terms) : of_energy<H, true, false>(terms);
  return terms.alpha ? of_energy<H, false, true>(terms) : of_energy<H, false, false>(terms);
}

} // namespace

std::vector<int> rows_of_threads(const long* offset, int owned, int T) {
  const long total = offset[owned];
  std::vector<int> first_row(T + 1, owned);
  for (int q = 0; q < T; ++q)
    first_row[q] =
        static_cast<int>(std::lower_bound(offset, offset + owned, total * q / T) - offset);
  first_row[0] = 0;
  return first_row;
}

Sums half(const Arrays& a, Terms terms, SimdTarget target, int lo, int hi, const Output& out) {
#if MF_PD_X86
  if (target != SimdTarget::Baseline) return packed(a, terms, true, target, lo, hi, out);
#endif
  return of_terms<true>(terms)(a, lo, hi, out);
}

Sums full(const Arrays& a, Terms terms, SimdTarget target, int lo, int hi, const Output& out) {
#if MF_PD_X86
  if (target != SimdTarget::Baseline) return packed(a, terms, false, target, lo, hi, out);
#endif
  return of_terms<false>(terms)(a, lo, hi, out);
}

} // namespace rows
} // namespace mf::pd
