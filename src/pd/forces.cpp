#include "meshfree/pd/forces.hpp"
#include "meshfree/pd/bond_rows.hpp"
#include "meshfree/core/error.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <omp.h>

namespace mf::pd {

namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

using rows::Arrays;

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
rows::Output thread_output(int t, int lo, int owned, bool alpha, double* force, double* density,
                           double* s0_trial) {
  if (t == 0) return {force, density, s0_trial, 0};
  thread_local std::vector<double> own_f, own_w, own_s;
  const std::size_t len = static_cast<std::size_t>(owned - lo);
  rows::Output o{nullptr, density, s0_trial, lo};
  own_f.assign(3 * len, 0.0);
  o.f = own_f.data();
  if (density) own_w.assign(len, 0.0), o.w = own_w.data();
  if (alpha) own_s.assign(len, kNone), o.s0n = own_s.data();
  return o;
}

/// What a force evaluation writes besides the rows' outputs: with the LAMMPS rule, a particle
/// no intact bond gave a trial s0 keeps its committed one (ghosts get theirs from their owners).
struct Ends {
  int points = 0;                  // owned and ghosts
  const double* s0_committed = nullptr; // null without the LAMMPS rule
};

/// The last pass of an evaluation, a work-sharing loop over every point of the enclosing
/// parallel region, after all rows: the buffers of threads 1.. added to the outputs in thread
/// order (owned particles; none with one thread), then the s0 fallback. Each point is finished by
/// one thread, so the pass needs no barrier of its own (nowait: the region's end is one).
void finish_points(const std::vector<int>& first_row, const std::vector<rows::Output>& out, int T,
                   int owned, const Ends& ends, double* force, double* density, double* s0_trial) {
  const double* const s0 = ends.s0_committed;
  if (T == 1 && !s0) return;
#pragma omp for schedule(static) nowait
  for (int i = 0; i < ends.points; ++i) {
    if (i < owned)
      for (int q = 1; q < T && first_row[q] <= i; ++q) {
        const std::ptrdiff_t iq = i - first_row[q];
        for (int d = 0; d < 3; ++d) force[3 * i + d] += out[q].f[3 * iq + d];
        if (density) density[i] += out[q].w[iq];
        if (s0) s0_trial[i] = std::max(s0_trial[i], out[q].s0n[iq]);
      }
    if (s0 && s0_trial[i] == kNone) s0_trial[i] = s0[i];
  }
}

/// Half layout: each stored pair evaluated once, Newton's third law. Thread t takes a range of
/// rows with an equal share of the bonds; its reactions on partners land in its own buffer over
/// [first row, owned) (thread 0 writes the outputs directly), and the buffers are added in thread
/// order afterwards. An owned-ghost pair gives its force to the owned particle only. One parallel
/// region with one barrier (between the rows and the sums): every thread finds the split itself,
/// since a thread that waits at a barrier sleeps, and waking it costs more than the split.
ForceReport half_loop(const Arrays& a, rows::Terms terms, SimdTarget target, const Ends& ends,
                      double* force, double* density, double* s0_trial) {
  const int owned = a.owned;
  long broken = 0;
  double energy = 0.0;
  std::vector<rows::Output> outputs(std::max(1, omp_get_max_threads()));
#pragma omp parallel reduction(+ : broken, energy)
  {
    const int T = omp_get_num_threads(), t = omp_get_thread_num();
    const std::vector<int> first_row = rows_of_threads(a, T);
    const int lo = first_row[t], hi = first_row[t + 1];
    outputs[t] = thread_output(t, lo, owned, terms.alpha, force, density, s0_trial);
    const rows::Sums sums = rows::half(a, terms, target, lo, hi, outputs[t]);
    broken += sums.broken;
    energy += sums.energy;
#pragma omp barrier
    finish_points(first_row, outputs, T, owned, ends, force, density, s0_trial);
  }
  return {broken, energy};
}

/// Full layout: each owned particle sums its own row, in the order of its partners' global ids;
/// rows are independent, so the sums do not depend on the threads or the ranks.
ForceReport full_loop(const Arrays& a, rows::Terms terms, SimdTarget target, const Ends& ends,
                      double* force, double* density, double* s0_trial) {
  constexpr int kRows = 512; // rows handed to a thread at a time
  const rows::Output out{force, density, s0_trial, 0};
  const int chunks = (a.owned + kRows - 1) / kRows;
  long broken = 0;
#pragma omp parallel reduction(+ : broken)
  {
#pragma omp for schedule(dynamic, 1)
    for (int q = 0; q < chunks; ++q)
      broken +=
          rows::full(a, terms, target, q * kRows, std::min(a.owned, (q + 1) * kRows), out).broken;
    finish_points({}, {}, 1, a.owned, ends, force, density, s0_trial);
  }
  // The total in particle order, whatever the threads.
  double energy = 0.0;
  if (terms.energy)
    for (int i = 0; i < a.owned; ++i) energy += a.volume[i] * density[i];
  return {broken, energy};
}

/// The class whose law constants every class shares, or null.
const BondClass* one_law(const BondClass* classes, std::size_t count) {
  for (std::size_t k = 1; k < count; ++k) {
    const BondClass &a = classes[0], &b = classes[k];
    if (a.limit != b.limit || a.alpha_floor != b.alpha_floor || a.s00 != b.s00 ||
        a.alpha != b.alpha || a.yield != b.yield)
      return nullptr;
  }
  return count > 0 ? classes : nullptr;
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
                 m.particles.owned_count(),
                 static_cast<int>(y.size() / 3),
                 one_law(classes, b.classes.size())};
  const rows::Terms terms{plastic, alpha, with_energy};
  const SimdTarget target = simd_target();
  const Ends ends{n, alpha ? s.s0.committed.data() : nullptr};
  const ForceReport r =
      half ? half_loop(a, terms, target, ends, force.data(), density, s0_trial)
           : full_loop(a, terms, target, ends, force.data(), density, s0_trial);
  if (alpha) s.s0.commit();
  return r;
}

} // namespace mf::pd
