#include "meshfree/pd/forces.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <omp.h>

namespace mf::pd {

namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

/// What the loops read and write, as raw arrays.
struct Arrays {
  const double* y;
  const long* offset;
  const int* partner;
  const std::uint32_t* cls;
  const BondClass* classes;
  unsigned char* intact;
  double* plastic;
  const double* s0; // committed s0 of the LAMMPS rule
  const double* volume;
  int owned;
};

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

/// The critical stretch of a bond: the law's, or with the LAMMPS rule min(s0_i, s0_j) of the
/// previous evaluation (pair_peri_pmb.cpp, PairPeriPMB::compute) where the law breaks.
template <bool Alpha>
inline double critical(const BondClass& c, const Arrays& a, double s0_i, int j) {
  if constexpr (Alpha)
    return std::max(std::min(s0_i, a.s0[j]), c.alpha_floor);
  else
    return c.limit;
}

/// The first row of each of T threads, for an equal share of the bonds each (T + 1 entries,
/// the last `owned`).
std::vector<int> rows_of_threads(const Arrays& a, int T) {
  const int owned = a.owned;
  const long total = a.offset[owned];
  std::vector<int> first_row(T + 1, owned);
  for (int q = 0; q < T; ++q)
    first_row[q] =
        static_cast<int>(std::lower_bound(a.offset, a.offset + owned, total * q / T) - a.offset);
  first_row[0] = 0;
  return first_row;
}

/// Where a thread of the half loop writes force, energy density and trial s0: thread 0 to the
/// outputs, another thread to its own zeroed buffers over [lo, owned), element 0 at row `base`.
struct ThreadOutput {
  double* f;
  double* w;
  double* s0n;
  int base;
};

ThreadOutput thread_output(int t, int lo, int owned, bool alpha, double* force, double* density,
                           double* s0_trial) {
  if (t == 0) return {force, density, s0_trial, 0};
  thread_local std::vector<double> own_f, own_w, own_s;
  const std::size_t len = static_cast<std::size_t>(owned - lo);
  ThreadOutput o{nullptr, density, s0_trial, lo};
  own_f.assign(3 * len, 0.0);
  o.f = own_f.data();
  if (density) own_w.assign(len, 0.0), o.w = own_w.data();
  if (alpha) own_s.assign(len, kNone), o.s0n = own_s.data();
  return o;
}

/// Adds the buffers of threads 1.. to the outputs, in thread order (a work-sharing loop of the
/// enclosing parallel region).
void add_thread_outputs(const std::vector<int>& first_row, const std::vector<ThreadOutput>& out,
                        int owned, bool alpha, double* force, double* density, double* s0_trial) {
  const int T = static_cast<int>(out.size());
#pragma omp for schedule(static)
  for (int i = 0; i < owned; ++i)
    for (int q = 1; q < T && first_row[q] <= i; ++q) {
      const std::ptrdiff_t iq = i - first_row[q];
      for (int d = 0; d < 3; ++d) force[3 * i + d] += out[q].f[3 * iq + d];
      if (density) density[i] += out[q].w[iq];
      if (alpha) s0_trial[i] = std::max(s0_trial[i], out[q].s0n[iq]);
    }
}

/// Half layout: each stored pair evaluated once, Newton's third law. Thread t takes a range of
/// rows with an equal share of the bonds; its reactions on partners land in its own buffer over
/// [first row, owned) (thread 0 writes the outputs directly), and the buffers are added in thread
/// order afterwards. An owned-ghost pair gives its force to the owned particle only.
template <bool Plastic, bool Alpha, bool Energy>
ForceReport half_loop(const Arrays& a, double* force, double* density, double* s0_trial) {
  const int owned = a.owned;
  long broken = 0;
  double energy = 0.0;
  std::vector<int> first_row;
  std::vector<ThreadOutput> outputs;
#pragma omp parallel reduction(+ : broken, energy)
  {
    const int T = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
    {
      first_row = rows_of_threads(a, T);
      outputs.resize(T);
    }
    const int lo = first_row[t], hi = first_row[t + 1];
    const ThreadOutput out = thread_output(t, lo, owned, Alpha, force, density, s0_trial);
    outputs[t] = out;
    double* const f = out.f;
    double* const w = out.w;
    double* const s0n = out.s0n;
    const int base = out.base;
    for (int i = lo; i < hi; ++i) {
      const double xi = a.y[3 * i], yi = a.y[3 * i + 1], zi = a.y[3 * i + 2];
      const double s0_i = Alpha ? a.s0[i] : 0.0;
      double fx = 0.0, fy = 0.0, fz = 0.0, wi = 0.0, s0_next = kNone;
      for (long k = a.offset[i]; k < a.offset[i + 1]; ++k) {
        if (!a.intact[k]) continue;
        const int j = a.partner[k];
        const BondClass& c = a.classes[a.cls[k]];
        const double dx = a.y[3 * j] - xi, dy = a.y[3 * j + 1] - yi, dz = a.y[3 * j + 2] - zi;
        const Bond<Plastic> bond(c, dx * dx + dy * dy + dz * dz, Plastic ? &a.plastic[k] : nullptr);
        const double g = bond.e * bond.inv_r;
        const double gi = c.cw * g, gj = c.cw_partner * g;
        fx += gi * dx, fy += gi * dy, fz += gi * dz;
        const bool j_owned = j < owned;
        const std::ptrdiff_t jb = j - base;
        if (j_owned) f[3 * jb] -= gj * dx, f[3 * jb + 1] -= gj * dy, f[3 * jb + 2] -= gj * dz;
        if constexpr (Energy) {
          // w = c (s - s_p)^2 |xi| / 2 per bond, half of it to each end.
          const double half_w = 0.25 * bond.e * bond.e * c.length;
          wi += c.cw * half_w;
          if (j_owned) {
            energy += a.volume[j] * c.cw_partner * half_w;
            if (w) w[jb] += c.cw_partner * half_w;
          }
        }
        if constexpr (Alpha) {
          // LAMMPS: s0 follows the most compressed intact bond, s00 - alpha s.
          const double candidate = c.s00 - c.alpha * bond.s;
          s0_next = std::max(s0_next, candidate);
          if (j_owned) s0n[jb] = std::max(s0n[jb], candidate);
        }
        if (bond.s > critical<Alpha>(c, a, s0_i, j)) {
          a.intact[k] = 0;
          broken += j_owned ? 2 : 1;
        }
      }
      const std::ptrdiff_t ib = i - base;
      f[3 * ib] += fx, f[3 * ib + 1] += fy, f[3 * ib + 2] += fz;
      if constexpr (Energy) {
        energy += a.volume[i] * wi;
        if (w) w[ib] += wi;
      }
      if constexpr (Alpha) s0n[ib] = std::max(s0n[ib], s0_next);
    }
#pragma omp barrier
    if (T > 1) add_thread_outputs(first_row, outputs, owned, Alpha, force, density, s0_trial);
  }
  return {broken, energy};
}

/// Full layout: each owned particle sums its own row, in the order of its partners' global ids;
/// rows are independent, so the sums do not depend on the threads or the ranks.
template <bool Plastic, bool Alpha, bool Energy>
ForceReport full_loop(const Arrays& a, double* force, double* density, double* s0_trial) {
  long broken = 0;
#pragma omp parallel for schedule(dynamic, 512) reduction(+ : broken)
  for (int i = 0; i < a.owned; ++i) {
    const double xi = a.y[3 * i], yi = a.y[3 * i + 1], zi = a.y[3 * i + 2];
    const double s0_i = Alpha ? a.s0[i] : 0.0;
    double fx = 0.0, fy = 0.0, fz = 0.0, wi = 0.0, s0_next = kNone;
    for (long k = a.offset[i]; k < a.offset[i + 1]; ++k) {
      if (!a.intact[k]) continue;
      const int j = a.partner[k];
      const BondClass& c = a.classes[a.cls[k]];
      const double dx = a.y[3 * j] - xi, dy = a.y[3 * j + 1] - yi, dz = a.y[3 * j + 2] - zi;
      const Bond<Plastic> bond(c, dx * dx + dy * dy + dz * dz, Plastic ? &a.plastic[k] : nullptr);
      const double gi = c.cw * bond.e * bond.inv_r;
      fx += gi * dx, fy += gi * dy, fz += gi * dz;
      if constexpr (Energy) wi += c.cw * (0.25 * bond.e * bond.e * c.length);
      if constexpr (Alpha) s0_next = std::max(s0_next, c.s00 - c.alpha * bond.s);
      if (bond.s > critical<Alpha>(c, a, s0_i, j)) {
        a.intact[k] = 0;
        ++broken;
      }
    }
    force[3 * i] = fx, force[3 * i + 1] = fy, force[3 * i + 2] = fz;
    if constexpr (Energy) density[i] = wi;
    if constexpr (Alpha) s0_trial[i] = s0_next;
  }
  // The total in particle order, whatever the threads.
  double energy = 0.0;
  if (Energy)
    for (int i = 0; i < a.owned; ++i) energy += a.volume[i] * density[i];
  return {broken, energy};
}

template <bool Plastic, bool Alpha>
ForceReport dispatch_energy(bool half, bool energy, const Arrays& a, double* f, double* w,
                            double* s0) {
  if (half)
    return energy ? half_loop<Plastic, Alpha, true>(a, f, w, s0)
                  : half_loop<Plastic, Alpha, false>(a, f, w, s0);
  return energy ? full_loop<Plastic, Alpha, true>(a, f, w, s0)
                : full_loop<Plastic, Alpha, false>(a, f, w, s0);
}

bool same_laws(const std::vector<materials::BondLaw>& a, const std::vector<materials::BondLaw>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].c != b[k].c || a[k].critical_stretch != b[k].critical_stretch ||
        a[k].yield_stretch != b[k].yield_stretch || a[k].alpha != b[k].alpha)
      return false;
  return true;
}

} // namespace

ForceReport bond_forces(const Model& m, BondState& s, const std::vector<double>& y,
                        std::vector<double>& force, bool with_energy,
                        std::vector<double>* energy_density) {
  const int n = m.particles.size();
  const Bonds& b = m.bonds;
  const bool half = b.layout == BondLayout::Half;
  const bool plastic = !s.plastic.empty();
  const bool alpha = !s.s0.empty();
  force.assign(3 * static_cast<std::size_t>(n), 0.0);
  // Full rows write every particle's energy density: a scratch array when none is asked for.
  thread_local std::vector<double> scratch;
  double* density = nullptr;
  if (energy_density) {
    energy_density->assign(n, 0.0);
    density = energy_density->data();
  } else if (!half) {
    scratch.resize(n);
    density = scratch.data();
  }
  double* s0_trial = nullptr;
  if (alpha) {
    std::fill(s.s0.trial.begin(), s.s0.trial.end(), kNone);
    s0_trial = s.s0.trial.data();
  }
  const BondClass* classes = b.classes.data();
  if (!same_laws(m.laws, b.folded)) {
    thread_local std::vector<BondClass> refolded;
    refolded = b.classes;
    fold_laws(refolded, m.laws);
    classes = refolded.data();
  }
  const Arrays a{y.data(),
                 b.offset.data(),
                 b.partner.data(),
                 b.cls.data(),
                 classes,
                 s.intact.data(),
                 plastic ? s.plastic.data() : nullptr,
                 alpha ? s.s0.committed.data() : nullptr,
                 m.particles.volume.data(),
                 m.particles.owned_count()};
  double* f = force.data();
  ForceReport r;
  if (plastic)
    r = alpha ? dispatch_energy<true, true>(half, with_energy, a, f, density, s0_trial)
              : dispatch_energy<true, false>(half, with_energy, a, f, density, s0_trial);
  else
    r = alpha ? dispatch_energy<false, true>(half, with_energy, a, f, density, s0_trial)
              : dispatch_energy<false, false>(half, with_energy, a, f, density, s0_trial);
  if (alpha) {
    // A particle with no intact bond keeps its s0; ghosts get theirs from their owners.
    for (int i = 0; i < n; ++i)
      if (s.s0.trial[i] == kNone) s.s0.trial[i] = s.s0.committed[i];
    s.s0.commit();
  }
  return r;
}

} // namespace mf::pd
