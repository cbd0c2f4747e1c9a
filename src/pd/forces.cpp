#include "meshfree/pd/forces.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/pd/bond_rows.hpp"
#include "meshfree/pd/spin_barrier.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <omp.h>

namespace mf::pd {

namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

using rows::Arrays;

std::vector<int> rows_of_threads(const Arrays& a, int T) {
  return rows::rows_of_threads(a.offset, a.owned, T);
}

/// `v` holding n zeros from a 32-byte boundary: the first of them.
double* aligned_zeros(std::vector<double>& v, std::size_t n) {
  v.assign(n + 3, 0.0);
  const std::size_t misaligned = reinterpret_cast<std::uintptr_t>(v.data()) % 32;
  return v.data() + (misaligned ? (32 - misaligned) / sizeof(double) : 0);
}

/// Where a thread of the half loop writes force, energy density and trial s0: forces to a zeroed
/// buffer of its own over [lo, owned), four doubles a point, element 0 at row `base` = lo;
/// energy density and trial s0 to the outputs (thread 0) or to zeroed buffers of its own.
rows::Output thread_output(int t, int lo, int owned, bool alpha, double* density,
                           double* s0_trial) {
  thread_local std::vector<double> own_f, own_w, own_s;
  const std::size_t len = static_cast<std::size_t>(owned - lo);
  rows::Output o{aligned_zeros(own_f, 4 * len), density, s0_trial, lo};
  if (t == 0) return o;
  if (density) own_w.assign(len, 0.0), o.w = own_w.data();
  if (alpha) own_s.assign(len, kNone), o.s0n = own_s.data();
  return o;
}

/// The last pass of an evaluation, a work-sharing loop over every point of the enclosing
/// parallel region, after all rows: the half layout's buffers added to the outputs in thread
/// order (owned particles; `T` threads, 0 for the full layout, which has none), then, with the
/// LAMMPS rule (s0 not null), the s0 of a particle no intact bond gave a trial one kept (ghosts
/// get theirs from their owners). Each point is finished by one thread: no barrier of its own
/// (nowait).
void finish_points(const std::vector<int>& first_row, const std::vector<rows::Output>& out, int T,
                   int owned, int points, const double* s0, double* force, double* density,
                   double* s0_trial) {
  if (T == 0 && !s0) return;
#pragma omp for schedule(static) nowait
  for (int i = 0; i < points; ++i) {
    if (i < owned)
      for (int q = 0; q < T && first_row[q] <= i; ++q) {
        const std::ptrdiff_t iq = i - first_row[q];
        for (int d = 0; d < 3; ++d) force[3 * i + d] += out[q].f[4 * iq + d];
        if (q == 0) continue; // its energy density and s0 are in the outputs
        if (density) density[i] += out[q].w[iq];
        if (s0) s0_trial[i] = std::max(s0_trial[i], out[q].s0n[iq]);
      }
    if (s0 && s0_trial[i] == kNone) s0_trial[i] = s0[i];
  }
}

/// Half layout, a thread's rows: each stored pair evaluated once, Newton's third law. Thread t
/// takes a range of rows with an equal share of the bonds; its forces, reactions on partners
/// included, land in its own buffer over [first row, owned), added in thread order by
/// finish_points. An owned-ghost pair gives its force to the owned particle only.
rows::Sums half_rows(const Arrays& a, rows::Terms terms, SimdTarget target, int T, int t,
                     rows::Output& out, double* density, double* s0_trial) {
  const std::vector<int> first_row = rows_of_threads(a, T);
  out = thread_output(t, first_row[t], a.owned, terms.alpha, density, s0_trial);
  return rows::half(a, terms, target, first_row[t], first_row[t + 1], out);
}

/// Full layout, a thread's rows: each owned particle sums its own row, in the order of its
/// partners' global ids; rows are independent, so the sums do not depend on the threads or the
/// ranks. Chunks of rows are handed out in turn (nowait: the caller waits for all).
long full_rows(const Arrays& a, rows::Terms terms, SimdTarget target, const rows::Output& out) {
  constexpr int kRows = 512; // rows handed to a thread at a time
  const int chunks = (a.owned + kRows - 1) / kRows;
  long broken = 0;
#pragma omp for schedule(dynamic, 1) nowait
  for (int q = 0; q < chunks; ++q)
    broken +=
        rows::full(a, terms, target, q * kRows, std::min(a.owned, (q + 1) * kRows), out).broken;
  return broken;
}

/// The positions y (three doubles a point) as the rows read them: four a point, the fourth 0,
/// from a 32-byte boundary.
const double* padded_positions(const std::vector<double>& y) {
  thread_local std::vector<double> padded;
  const std::size_t points = y.size() / 3;
  double* const p = aligned_zeros(padded, 4 * points);
  for (std::size_t i = 0; i < points; ++i)
    for (int d = 0; d < 3; ++d) p[4 * i + d] = y[3 * i + d];
  return p;
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

BondForcePass::BondForcePass(const Model& m, BondState& s, const std::vector<double>& y,
                             std::vector<double>& force, bool with_energy,
                             std::vector<double>* energy_density)
    : s_(s), a_{}, points_(m.particles.size()) {
  const int n = points_;
  const Bonds& b = m.bonds;
  half_ = b.layout == BondLayout::Half;
  const bool plastic = !s.plastic.empty();
  const bool alpha = !s.s0.empty();
  force.assign(3 * static_cast<std::size_t>(n), 0.0);
  force_ = force.data();
  // Full rows write every particle's energy density: a scratch array when none is asked for.
  thread_local std::vector<double> scratch;
  density_ = nullptr;
  if (energy_density) {
    energy_density->assign(n, 0.0);
    density_ = energy_density->data();
  } else if (!half_) {
    scratch.resize(n);
    density_ = scratch.data();
  }
  s0_trial_ = nullptr;
  if (alpha) {
    std::fill(s.s0.trial.begin(), s.s0.trial.end(), kNone);
    s0_trial_ = s.s0.trial.data();
  }
  const BondClass* classes = b.classes.data();
  if (!same_laws(m.laws, b.folded)) {
    thread_local std::vector<BondClass> refolded;
    refolded = b.classes;
    fold_laws(refolded, m.laws);
    classes = refolded.data();
  }
  a_ = Arrays{padded_positions(y),
              b.offset.data(),
              b.partner.data(),
              b.cls.view(),
              classes,
              s.intact.data(),
              plastic ? s.plastic.data() : nullptr,
              alpha ? s.s0.committed.data() : nullptr,
              m.particles.volume.data(),
              m.particles.owned_count(),
              static_cast<int>(y.size() / 3),
              one_law(classes, b.classes.size())};
  terms_ = rows::Terms{plastic, alpha, with_energy};
  target_ = simd_target();
  const int threads = std::max(omp_get_max_threads(), omp_get_num_threads());
  outputs_.resize(threads);
  broken_.assign(threads, 0);
  energy_.assign(threads, 0.0);
}

void BondForcePass::rows() {
  const int T = omp_get_num_threads(), t = omp_get_thread_num();
  if (half_) {
    const rows::Sums sums = half_rows(a_, terms_, target_, T, t, outputs_[t], density_, s0_trial_);
    broken_[t] = sums.broken;
    energy_[t] = sums.energy;
  } else {
    broken_[t] = full_rows(a_, terms_, target_, {force_, density_, s0_trial_, 0});
  }
}

void BondForcePass::finish() {
  const int T = omp_get_num_threads();
  const std::vector<int> first_row = half_ ? rows_of_threads(a_, T) : std::vector<int>{};
  finish_points(first_row, outputs_, half_ ? T : 0, a_.owned, points_, a_.s0, force_, density_,
                s0_trial_);
}

ForceReport BondForcePass::report() {
  ForceReport r;
  for (std::size_t t = 0; t < broken_.size(); ++t)
    r.broken += broken_[t], r.strain_energy += energy_[t];
  // Full layout: the total in particle order, whatever the threads.
  if (!half_ && terms_.energy)
    for (int i = 0; i < a_.owned; ++i) r.strain_energy += a_.volume[i] * density_[i];
  if (terms_.alpha) s_.s0.commit();
  return r;
}

ForceReport bond_forces(const Model& m, BondState& s, const std::vector<double>& y,
                        std::vector<double>& force, bool with_energy,
                        std::vector<double>* energy_density) {
  BondForcePass pass(m, s, y, force, with_energy, energy_density);
  SpinBarrier barrier;
#pragma omp parallel
  {
    pass.rows();
    barrier.wait();
    pass.finish();
  }
  return pass.report();
}

} // namespace mf::pd
