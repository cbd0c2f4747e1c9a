// The passes of the LPS force (pd/state_based.hpp) over the bond rows: dilatation, (EPS) the
// trial deviatoric norms, then forces, each a parallel loop over rows. In the half layout a
// thread's contributions to other rows go to buffers of its own, added in thread order (as
// pd/forces does); in the full layout every row sums its own bonds in its partners' global-id
// order, so the sums do not depend on the threads or the ranks.
#include "meshfree/pd/state_based.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/pd/bond_rows.hpp"
#include "meshfree/pd/state_surface.hpp"
#include "state_rows.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <omp.h>

namespace mf::pd {

using namespace detail;

namespace {

/// The influence function of every bond class.
std::vector<double> class_influence(const Model& m) {
  std::vector<double> omega(m.bonds.classes.size());
  for (std::size_t c = 0; c < omega.size(); ++c)
    omega[c] = materials::influence(m.influence, m.bonds.classes[c].length, m.horizon);
  return omega;
}

/// A thread's buffers for the half layout's contributions to rows [lo, owned).
struct Buffers {
  int lo = 0;
  std::vector<double> sum, f, w, s0; // a per-particle sum (dilatation, norm), forces, energy, s0
};

std::vector<Buffers>& thread_buffers(int T) {
  static std::vector<Buffers> buffers;
  if (static_cast<int>(buffers.size()) < T) buffers.resize(T);
  return buffers;
}

/// Pass 1, a thread's rows [lo, hi): sum_j omega |xi| e w_ij into theta (row particle) and,
/// in the half layout, sum_i omega |xi| e w_ji into the partner's slot of `other` (element 0 at
/// row `base`).
void dilatation_rows(const Family& f, int lo, int hi, double* theta, double* other, int base) {
  for (int i = lo; i < hi; ++i) {
    const double xi = f.y[3 * i], yi = f.y[3 * i + 1], zi = f.y[3 * i + 2];
    double sum = 0.0;
    for (long k = f.offset[i]; k < f.offset[i + 1]; ++k) {
      if (!f.intact[k]) continue;
      const int j = f.partner[k];
      const BondClass& c = f.classes[f.cls[k]];
      const double q = f.omega[f.cls[k]] * c.length * stretch_of(f, j, c, xi, yi, zi).e;
      sum += q * c.weight;
      if (f.half && j < f.owned) other[j - base] += q * c.weight_partner;
    }
    theta[i - (f.half ? base : 0)] += sum;
  }
}

/// Pass 1 of a position-aware body, a thread's rows [lo, hi): three sums a particle, with each
/// end's factors: sum_j omega dil |xi| e w_ij (the dilatation's), P_i = sum_j omega dev |xi| e
/// w_ij and S_i = sum_j omega dev |xi|^2 w_ij (Q_i = b_i (P_i - theta_i S_i / d)).
void aware_dilatation_rows(const Family& f, int lo, int hi, double* into, double* other, int base) {
  for (int i = lo; i < hi; ++i) {
    const double xi = f.y[3 * i], yi = f.y[3 * i + 1], zi = f.y[3 * i + 2];
    double sum[3] = {0.0, 0.0, 0.0};
    for (long k = f.offset[i]; k < f.offset[i + 1]; ++k) {
      if (!f.intact[k]) continue;
      const int j = f.partner[k];
      const BondClass& c = f.classes[f.cls[k]];
      const double oL = f.omega[f.cls[k]] * c.length, e = stretch_of(f, j, c, xi, yi, zi).e;
      sum[0] += oL * e * c.dil * c.weight;
      sum[1] += oL * e * c.dev * c.weight;
      sum[2] += oL * c.length * c.dev * c.weight;
      if (f.half && j < f.owned) {
        double* to = other + 3 * (j - base);
        to[0] += oL * e * c.dil_partner * c.weight_partner;
        to[1] += oL * e * c.dev_partner * c.weight_partner;
        to[2] += oL * c.length * c.dev_partner * c.weight_partner;
      }
    }
    double* to = into + 3 * (i - (f.half ? base : 0));
    for (int e = 0; e < 3; ++e) to[e] += sum[e];
  }
}

/// Pass 2, a thread's rows [lo, hi): the force of each intact bond on its row's particle (and,
/// half layout, the reaction on an owned partner), the deviatoric energy, the plastic return of
/// both ends' deviatoric extensions, the LAMMPS rule's s0, breaking after the force has counted.
/// Returns directed bonds broken.
template <bool kAware>
long force_rows(const Family& f, const StateTerms& t, int lo, int hi, const PassOut& out) {
  long broken = 0;
  const double d = f.d;
  for (int i = lo; i < hi; ++i) {
    const double xi = f.y[3 * i], yi = f.y[3 * i + 1], zi = f.y[3 * i + 2];
    const double iso_i = t.iso[i], bi = t.b[i], ti = t.theta[i] / d;
    const double sc_i = t.scale ? t.scale[i] : 1.0;
    const double s0_i = t.s0 ? t.s0[i] : 0.0;
    double fx = 0.0, fy = 0.0, fz = 0.0, wi = 0.0, s0_next = kNone;
    for (long k = f.offset[i]; k < f.offset[i + 1]; ++k) {
      if (!f.intact[k]) continue;
      const int j = f.partner[k];
      const BondClass& c = f.classes[f.cls[k]];
      const double omega = f.omega[f.cls[k]], L = c.length;
      const Stretch s = stretch_of(f, j, c, xi, yi, zi);
      const double tj_d = t.theta[j] / d, sc_j = t.scale ? t.scale[j] : 1.0;
      const double el_i = elastic_deviatoric(s.e, ti, L, t.plastic, 2 * k);
      const double el_j = elastic_deviatoric(s.e, tj_d, L, t.plastic, 2 * k + 1);
      // The position-aware factors of both ends (pd/state_surface.hpp), 1 in the LPS.
      const double di = kAware ? c.dil : 1.0, dj = kAware ? c.dil_partner : 1.0;
      const double vi = kAware ? c.dev : 1.0, vj = kAware ? c.dev_partner : 1.0;
      const double T =
          kAware ? omega * ((iso_i * di + t.iso[j] * dj) * L + sc_i * bi * vi * el_i +
                            sc_j * t.b[j] * vj * el_j)
                 : omega * ((iso_i + t.iso[j]) * L + sc_i * bi * el_i + sc_j * t.b[j] * el_j);
      if (t.plastic) {
        // The return to the yield surface: e^dp = e^d - scale (e^d - e^dp_old).
        t.plastic[2 * k] = s.e - ti * L - sc_i * el_i;
        t.plastic[2 * k + 1] = s.e - tj_d * L - sc_j * el_j;
      }
      const double g = s.r > 0.0 ? T / s.r : 0.0;
      const double gi = g * c.weight;
      fx += gi * s.dx, fy += gi * s.dy, fz += gi * s.dz;
      const bool j_row = f.half && j < f.owned;
      const std::ptrdiff_t jb = j - out.base;
      if (j_row) {
        const double gj = g * c.weight_partner;
        out.f[3 * jb] -= gj * s.dx, out.f[3 * jb + 1] -= gj * s.dy, out.f[3 * jb + 2] -= gj * s.dz;
      }
      if (t.energy) {
        const double ei = sc_i * el_i, ej = sc_j * el_j; // elastic parts after the return
        wi += 0.5 * bi * (kAware ? vi * omega : omega) * ei * ei * c.weight;
        if (j_row)
          out.w[jb] += 0.5 * t.b[j] * (kAware ? vj * omega : omega) * ej * ej * c.weight_partner;
      }
      const double stretch = s.e / L;
      if (t.s0) {
        const double candidate = c.s00 - c.alpha * stretch;
        s0_next = std::max(s0_next, candidate);
        if (j_row) out.s0n[jb] = std::max(out.s0n[jb], candidate);
      }
      if (t.breaking && stretch > critical(c, t.s0, s0_i, j)) {
        f.intact[k] = 0;
        broken += j_row ? 2 : 1;
      }
    }
    const std::ptrdiff_t ib = i - out.base;
    out.f[3 * ib] += fx, out.f[3 * ib + 1] += fy, out.f[3 * ib + 2] += fz;
    if (t.energy) out.w[ib] += wi + 0.5 * t.kappa[i] * t.theta[i] * t.theta[i];
    if (t.s0) out.s0n[ib] = std::max(out.s0n[ib], s0_next);
  }
  return broken;
}

/// The plastic pass between the two, a thread's rows [lo, hi): the squared norm of each
/// particle's trial deviatoric force state, sum_j (b_i omega (e^d - e^dp))^2 w_ij, into `norm`
/// (row particle) and, half layout, the partner's into `other` (element 0 at row `base`).
void trial_norm_rows(const Family& f, const StateTerms& t, int lo, int hi, double* norm,
                     double* other, int base) {
  const double d = f.d;
  for (int i = lo; i < hi; ++i) {
    const double xi = f.y[3 * i], yi = f.y[3 * i + 1], zi = f.y[3 * i + 2];
    const double ti = t.theta[i] / d;
    double sum = 0.0;
    for (long k = f.offset[i]; k < f.offset[i + 1]; ++k) {
      if (!f.intact[k]) continue;
      const int j = f.partner[k];
      const BondClass& c = f.classes[f.cls[k]];
      const double omega = f.omega[f.cls[k]];
      const double e = stretch_of(f, j, c, xi, yi, zi).e;
      const double td_i = t.b[i] * omega * elastic_deviatoric(e, ti, c.length, t.plastic, 2 * k);
      sum += td_i * td_i * c.weight;
      if (f.half && j < f.owned) {
        const double td_j =
            t.b[j] * omega * elastic_deviatoric(e, t.theta[j] / d, c.length, t.plastic, 2 * k + 1);
        other[j - base] += td_j * td_j * c.weight_partner;
      }
    }
    norm[i - (f.half ? base : 0)] += sum;
  }
}

/// Adds the half layout's thread buffers over [first_row[q], owned) into `sum` in thread order,
/// `per` values a point (a work-sharing loop of the enclosing region).
void add_buffers(const std::vector<int>& rows_of, std::vector<Buffers>& buf, int T, int owned,
                 int per, std::vector<double> Buffers::*field, double* sum, bool maximum) {
#pragma omp for schedule(static)
  for (int i = 0; i < owned; ++i)
    for (int q = 1; q < T && rows_of[q] <= i; ++q) {
      const std::vector<double>& v = buf[q].*field;
      for (int e = 0; e < per; ++e) {
        double& to = sum[per * i + e];
        const double from = v[per * (i - rows_of[q]) + e];
        to = maximum ? std::max(to, from) : to + from;
      }
    }
}

/// The family's arrays of a model at positions y.
Family family_of(const Model& m, BondState& s, const std::vector<double>& y,
                 const std::vector<double>& omega) {
  const Bonds& b = m.bonds;
  return Family{y.data(),
                b.offset.data(),
                b.partner.data(),
                b.cls.view(),
                b.classes.data(),
                omega.data(),
                s.intact.data(),
                m.particles.owned_count(),
                b.layout == BondLayout::Half,
                m.position_aware,
                static_cast<double>(materials::pd_dimensions(m.dimension))};
}

/// Per-particle sums (`per` a particle) over the bonds of every owned row into `sum` (zeroed
/// first): `rows(lo, hi, into, other, base)` adds a row's own part to into[per (i - base)] (base
/// 0 in the full layout) and, in the half layout, the partners' parts to other[per (j - base)];
/// the half layout's threads past the first add into buffers of their own, summed in thread
/// order.
template <class Rows>
void particle_sums(const Family& f, std::vector<double>& sum, const Rows& rows, int per = 1) {
  const int owned = f.owned;
  std::fill(sum.begin(), sum.end(), 0.0);
  std::vector<Buffers>& buf = thread_buffers(omp_get_max_threads());
#pragma omp parallel
  {
    const int T = omp_get_num_threads(), q = omp_get_thread_num();
    const std::vector<int> first = rows::rows_of_threads(f.offset, owned, T);
    if (f.half) {
      Buffers& own = buf[q];
      own.lo = q == 0 ? 0 : first[q];
      own.sum.assign(q == 0 ? 0 : static_cast<std::size_t>(per) * (owned - own.lo), 0.0);
      double* into = q == 0 ? sum.data() : own.sum.data();
      rows(first[q], first[q + 1], into, into, own.lo);
#pragma omp barrier
      add_buffers(first, buf, T, owned, per, &Buffers::sum, sum.data(), false);
    } else {
#pragma omp for schedule(dynamic, 512)
      for (int i = 0; i < owned; ++i) rows(i, i + 1, sum.data(), nullptr, 0);
    }
  }
}

/// Pass 1 over every owned row: theta_i = (d / m_i) sum_j omega |xi| e w_ij.
void dilatations(const Family& f, const Model& m, std::vector<double>& theta) {
  particle_sums(f, theta, [&f](int lo, int hi, double* into, double* other, int base) {
    if (f.y4)
      packed_dilatation_rows(f, lo, hi, into, other, base);
    else
      dilatation_rows(f, lo, hi, into, other, base);
  });
  for (int i = 0; i < f.owned; ++i) {
    const double mi = m.weighted_volume[i];
    theta[i] = mi > 0.0 ? f.d * theta[i] / mi : 0.0;
  }
}

/// Pass 1 of a position-aware body: theta_i = (d / m_i) sum_j omega dil |xi| e w_ij and Q_i =
/// b_i (P_i - theta_i S_i / d) (pd/state_surface.hpp) of every owned particle.
void aware_dilatations(const Family& f, const Model& m, std::vector<double>& theta,
                       std::vector<double>& Q) {
  thread_local std::vector<double> sums;
  sums.assign(3 * theta.size(), 0.0);
  particle_sums(
      f, sums,
      [&f](int lo, int hi, double* into, double* other, int base) {
        aware_dilatation_rows(f, lo, hi, into, other, base);
      },
      3);
  const double a = materials::lps_deviatoric_factor(m.dimension);
  for (int i = 0; i < f.owned; ++i) {
    const double mi = m.weighted_volume[i], *s = &sums[3 * static_cast<std::size_t>(i)];
    theta[i] = mi > 0.0 ? f.d * s[0] / mi : 0.0;
    const double bi = mi > 0.0 ? a * m.lps[m.particles.material[i]].mu / mi : 0.0;
    Q[i] = bi * (s[1] - theta[i] * s[2] / f.d);
  }
}

/// The plastic pass: every owned particle's return factor min(1, sqrt(2 psi0_i / |t_trial|^2))
/// (Mitchell 2011: the yield surface |t^d|^2 / 2 = psi0, a radial return).
void return_factors(const Family& f, const StateTerms& t, const Model& m,
                    std::vector<double>& scale) {
  particle_sums(f, scale, [&f, &t](int lo, int hi, double* into, double* other, int base) {
    trial_norm_rows(f, t, lo, hi, into, other, base);
  });
  for (int i = 0; i < f.owned; ++i) {
    const double limit = 2.0 * m.yield_value[i], norm = scale[i];
    scale[i] = norm > limit && limit > 0.0 ? std::sqrt(limit / norm) : 1.0;
  }
}

} // namespace

void set_weighted_volumes(Model& m, const BondState& s) {
  MF_REQUIRE(m.state_based(), "set_weighted_volumes: the body is bond-based");
  const std::vector<double> omega = class_influence(m);
  const Bonds& b = m.bonds;
  const int n = m.particles.size();
  std::vector<double> second(n, 0.0); // sum_j omega^2 |xi|^2 w_ij
  m.weighted_volume.assign(n, 0.0);
  for_each_directed_bond(m, [&](int i, int, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const double om = omega[&c - b.classes.data()], L2 = c.length * c.length;
    m.weighted_volume[i] += om * L2 * w;
    second[i] += om * om * L2 * w;
  });
  m.halo.exchange(m.weighted_volume);
  m.yield_value.clear();
  if (!m.state_plastic()) return;
  m.yield_value.assign(n, 0.0);
  for (int i = 0; i < m.particles.owned_count(); ++i)
    m.yield_value[i] = materials::eps_yield_value(m.lps[m.particles.material[i]].yield_stress,
                                                  second[i], m.weighted_volume[i]);
  m.halo.exchange(m.yield_value);
}

namespace {

/// Pass 2 over rows [lo, hi): packed where the positions are (an elastic body), else scalar.
long rows_of(const Family& f, const StateTerms& t, int lo, int hi, const PassOut& out) {
  if (f.y4 && !t.plastic) return packed_force_rows(f, t, lo, hi, out);
  return f.aware ? force_rows<true>(f, t, lo, hi, out) : force_rows<false>(f, t, lo, hi, out);
}

/// Pass 2 over every owned row, its outputs in `out` (base 0): in the half layout the threads past
/// the first write to buffers of their own, added in thread order. Returns directed bonds broken.
long force_pass(const Family& f, const StateTerms& t, const PassOut& out) {
  const int owned = f.owned;
  std::vector<Buffers>& buf = thread_buffers(omp_get_max_threads());
  long broken = 0;
#pragma omp parallel reduction(+ : broken)
  {
    const int T = omp_get_num_threads(), q = omp_get_thread_num();
    const std::vector<int> first = rows::rows_of_threads(f.offset, owned, T);
    if (f.half) {
      PassOut mine = out;
      if (q > 0) {
        Buffers& own = buf[q];
        own.lo = first[q];
        const std::size_t len = static_cast<std::size_t>(owned - own.lo);
        own.f.assign(3 * len, 0.0);
        own.w.assign(out.w ? len : 0, 0.0);
        own.s0.assign(out.s0n ? len : 0, kNone);
        mine = PassOut{own.f.data(), own.w.data(), own.s0.data(), own.lo};
      }
      broken += rows_of(f, t, first[q], first[q + 1], mine);
#pragma omp barrier
      add_buffers(first, buf, T, owned, 3, &Buffers::f, out.f, false);
      if (out.w) add_buffers(first, buf, T, owned, 1, &Buffers::w, out.w, false);
      if (out.s0n) add_buffers(first, buf, T, owned, 1, &Buffers::s0, out.s0n, true);
    } else {
#pragma omp for schedule(dynamic, 512)
      for (int i = 0; i < owned; ++i) broken += rows_of(f, t, i, i + 1, out);
    }
  }
  return broken;
}

/// The positions four doubles a point for the packed rows, null when the scalar rows run.
const double* padded_positions(const std::vector<double>& y, int n) {
  if (!packed_rows()) return nullptr;
  thread_local std::vector<double> y4;
  y4.resize(4 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int e = 0; e < 4; ++e) y4[4 * i + e] = e < 3 ? y[3 * i + e] : 0.0;
  return y4.data();
}

/// Pass 1 and its halo: every particle's dilatation and, position-aware, its Q_i.
void dilatation_pass(const Family& f, const Model& m, std::vector<double>& theta,
                     std::vector<double>& Q) {
  const int n = m.particles.size();
  theta.assign(n, 0.0);
  Q.assign(m.position_aware ? n : 0, 0.0);
  if (m.position_aware) {
    aware_dilatations(f, m, theta, Q);
    m.halo.exchange(Q);
  } else {
    dilatations(f, m, theta);
  }
  m.halo.exchange(theta); // the ghosts' dilatation, from their owners
}

/// Per particle, of its own material: iso_i = (d kappa theta_i - Q_i) / m_i, b_i = a mu / m_i
/// and kappa_i.
void particle_terms(const Model& m, double d, const std::vector<double>& theta,
                    const std::vector<double>& Q, std::vector<double>& iso, std::vector<double>& b,
                    std::vector<double>& kappa) {
  const int n = m.particles.size();
  iso.resize(n), b.resize(n), kappa.resize(n);
  const double a = materials::lps_deviatoric_factor(m.dimension);
  for (int i = 0; i < n; ++i) {
    const materials::LpsLaw& law = m.lps[m.particles.material[i]];
    const double mi = m.weighted_volume[i];
    b[i] = mi > 0.0 ? a * law.mu / mi : 0.0;
    iso[i] = mi <= 0.0   ? 0.0
             : Q.empty() ? d * law.kappa * theta[i] / mi
                         : (d * law.kappa * theta[i] - Q[i]) / mi;
    kappa[i] = law.kappa;
  }
}

/// The packed rows' partner columns: theta / d, iso, b and 0 a particle.
const double* partner_columns(const std::vector<double>& theta, const std::vector<double>& iso,
                              const std::vector<double>& b, double d) {
  thread_local std::vector<double> partner;
  partner.resize(4 * theta.size());
  for (std::size_t i = 0; i < theta.size(); ++i) {
    double* p = &partner[4 * i];
    p[0] = theta[i] / d, p[1] = iso[i], p[2] = b[i], p[3] = 0.0;
  }
  return partner.data();
}

ForceReport evaluate(const Model& m, BondState& s, const std::vector<double>& y,
                     std::vector<double>& force, bool with_energy,
                     std::vector<double>* energy_density, std::vector<double>* theta_out,
                     bool breaking) {
  MF_REQUIRE(m.weighted_volume.size() == static_cast<std::size_t>(m.particles.size()),
             "state_forces: the weighted volumes are not set (pd::set_weighted_volumes)");
  const int n = m.particles.size();
  const std::vector<double> omega = class_influence(m);
  Family f = family_of(m, s, y, omega);
  f.y4 = padded_positions(y, n);
  const int owned = f.owned;
  thread_local std::vector<double> theta, Q, iso, b, kappa, density, scale;
  dilatation_pass(f, m, theta, Q);
  particle_terms(m, f.d, theta, Q, iso, b, kappa);
  force.assign(3 * static_cast<std::size_t>(n), 0.0);
  double* w = nullptr;
  if (with_energy || energy_density) {
    density.assign(n, 0.0);
    w = density.data();
  }
  const bool alpha = !s.s0.empty();
  if (alpha) std::fill(s.s0.trial.begin(), s.s0.trial.end(), kNone);
  const bool plastic = !s.plastic.empty();
  StateTerms terms{iso.data(),
                   b.data(),
                   theta.data(),
                   kappa.data(),
                   alpha ? s.s0.committed.data() : nullptr,
                   w != nullptr,
                   breaking,
                   nullptr,
                   plastic ? s.plastic.data() : nullptr};
  if (f.y4 && !plastic) terms.partner = partner_columns(theta, iso, b, f.d);
  if (plastic) {
    scale.assign(n, 1.0);
    return_factors(f, terms, m, scale);
    m.halo.exchange(scale); // the ghosts' return, from their owners
    terms.scale = scale.data();
  }
  const long broken =
      force_pass(f, terms, {force.data(), w, alpha ? s.s0.trial.data() : nullptr, 0});
  ForceReport r;
  r.broken = broken;
  if (alpha) {
    for (int i = 0; i < n; ++i)
      if (s.s0.trial[i] == kNone) s.s0.trial[i] = s.s0.committed[i];
    s.s0.commit();
  }
  if (with_energy)
    for (int i = 0; i < owned; ++i) r.strain_energy += m.particles.volume[i] * w[i];
  if (energy_density) energy_density->assign(density.begin(), density.end());
  if (theta_out) theta_out->assign(theta.begin(), theta.end());
  return r;
}

} // namespace

ForceReport state_forces(const Model& m, BondState& s, const std::vector<double>& y,
                         std::vector<double>& force, bool with_energy,
                         std::vector<double>* energy_density, std::vector<double>* theta) {
  return evaluate(m, s, y, force, with_energy, energy_density, theta, true);
}

void state_forces_kept(const Model& m, const std::vector<unsigned char>& intact,
                       const std::vector<double>& plastic, const std::vector<double>& y,
                       std::vector<double>& force, std::vector<double>& energy_density) {
  BondState kept;
  kept.intact = intact;
  kept.plastic = plastic;
  evaluate(m, kept, y, force, false, &energy_density, nullptr, false);
}

std::vector<double> state_fictitious_density(const Model& m, const BondState& s) {
  if (m.position_aware) return position_aware_fictitious_density(m, s);
  const particles::ParticleSet& q = m.particles;
  const int n = q.size();
  const std::vector<double> omega = class_influence(m);
  const Bonds& bonds = m.bonds;
  const double d = materials::pd_dimensions(m.dimension);
  const double a = materials::lps_deviatoric_factor(m.dimension);
  // Per particle: b_i, |A_i| d / m_i and S_i.
  std::vector<double> b(n, 0.0), dil(n, 0.0), S(n, 0.0);
  for_each_directed_bond(m, [&](int i, int, long k, double w, const BondClass& c) {
    if (s.intact[k]) S[i] += omega[&c - bonds.classes.data()] * c.length * w;
  });
  m.halo.exchange(S); // a ghost partner's S_j, from its owner
  for (int i = 0; i < n; ++i) {
    const materials::LpsLaw& law = m.lps[q.material[i]];
    const double mi = m.weighted_volume[i];
    if (mi <= 0.0) continue;
    b[i] = a * law.mu / mi;
    dil[i] = std::abs(d * law.kappa - a * law.mu / d) / mi * d / mi;
  }
  const double root3 = std::sqrt(3.0);
  std::vector<double> lambda(3 * static_cast<std::size_t>(n), 0.0);
  for_each_directed_bond(m, [&](int i, int j, long k, double w, const BondClass& c) {
    if (!s.intact[k]) return;
    const double om = omega[&c - bonds.classes.data()], L = c.length;
    const double e[3] = {(q.X[3 * j] - q.X[3 * i]) / L, (q.X[3 * j + 1] - q.X[3 * i + 1]) / L,
                         (q.X[3 * j + 2] - q.X[3 * i + 2]) / L};
    const double row = std::abs(e[0]) + std::abs(e[1]) + std::abs(e[2]);
    const double deviatoric = om * (b[i] + b[j]) * w, partners = om * L * w * dil[j] * S[j];
    for (int e_d = 0; e_d < 3; ++e_d)
      lambda[3 * i + e_d] += 0.5 * deviatoric * std::abs(e[e_d]) * row + 0.5 * root3 * partners;
  });
  for (int i = 0; i < n; ++i)
    for (int e_d = 0; e_d < 3; ++e_d) lambda[3 * i + e_d] += 0.5 * root3 * dil[i] * S[i] * S[i];
  return lambda;
}

double state_stable_time_step(const Model& m, int iterations) {
  // Power iteration on a = -K u / rho, K the stiffness per unit volume at the reference
  // positions (central differences of the forces, none broken): the Rayleigh quotient in the
  // mass-weighted product approaches the highest eigenvalue omega_max^2 from below. The start
  // is a fixed pseudo-random field of the particles' global ids, the same on any ranks.
  const particles::ParticleSet& p = m.particles;
  const int n = p.size(), owned = p.owned_count();
  const distribution::Ranks& ranks = m.halo.ranks();
  std::vector<double> v(3 * static_cast<std::size_t>(n)), y, fp, fm, w;
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const std::uint64_t z =
          (static_cast<std::uint64_t>(p.id[i]) * 3 + d + 1) * 0x9E3779B97F4A7C15ull;
      v[3 * i + d] = static_cast<double>((z ^ (z >> 31)) % 2001) / 1000.0 - 1.0;
    }
  if (m.plane())
    for (int i = 0; i < n; ++i) v[3 * i + 2] = 0.0;
  std::vector<unsigned char> all(m.bonds.stored(), 1);
  const double h = 1e-6 * m.spacing;
  double lambda = 0.0;
  for (int it = 0; it < iterations; ++it) {
    double vmax = 0.0;
    for (int i = 0; i < owned; ++i)
      for (int d = 0; d < 3; ++d) vmax = std::max(vmax, std::abs(v[3 * i + d]));
    vmax = -ranks.min(-vmax);
    for (double& x : v) x /= vmax;
    m.halo.exchange(v, 3);
    y = p.X;
    for (std::size_t k = 0; k < y.size(); ++k) y[k] += h * v[k];
    state_forces_kept(m, all, {}, y, fp, w);
    y = p.X;
    for (std::size_t k = 0; k < y.size(); ++k) y[k] -= h * v[k];
    state_forces_kept(m, all, {}, y, fm, w);
    double vKv = 0.0, vMv = 0.0;
    for (int i = 0; i < owned; ++i)
      for (int d = 0; d < 3; ++d) {
        const std::size_t k = 3 * static_cast<std::size_t>(i) + d;
        const double Kv = -(fp[k] - fm[k]) / (2.0 * h);
        vKv += p.volume[i] * v[k] * Kv;
        vMv += p.volume[i] * p.density[i] * v[k] * v[k];
        v[k] = Kv / p.density[i];
      }
    lambda = ranks.sum(vKv) / ranks.sum(vMv);
  }
  return lambda > 0.0 ? 2.0 / std::sqrt(lambda) : std::numeric_limits<double>::infinity();
}

} // namespace mf::pd
