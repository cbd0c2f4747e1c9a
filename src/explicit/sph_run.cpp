#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/sph/decomposition.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mf::explicit_dynamics {

namespace {

std::vector<GaugePoint> gauge_points(const spec::SphSpec& s) {
  std::vector<GaugePoint> g;
  for (const auto& p : s.output.gauges) g.push_back({p.name, Vec3(p.at[0], p.at[1], p.at[2])});
  return g;
}

/// Where this rank's block of ids goes in the one field file (none on one rank).
io::PointSlice field_slice(const sph::Hydro& h, long total) {
  const distribution::Ranks& ranks = h.ranks;
  if (ranks.serial()) return {};
  const distribution::IdBlocks blocks{total, ranks.size};
  return {ranks.comm, static_cast<std::size_t>(blocks.first(ranks.rank)),
          static_cast<std::size_t>(total)};
}

/// The first `per` x owned values of `a`, as doubles.
template <class T>
io::FieldOutput::Fill owned_values(const sph::Hydro& h, const std::vector<T>& a, int per) {
  return [&h, &a, per](std::vector<double>& out) {
    out.assign(a.begin(), a.begin() + per * static_cast<std::size_t>(h.particles.owned_count()));
  };
}

/// Owned values (`per` a particle, local order) in this rank's block of global ids.
std::vector<double> in_id_order(const sph::Hydro& h, long total, const std::vector<double>& v,
                                int per) {
  if (h.ranks.serial()) return v; // the owned particles are the whole body, in id order
  return distribution::to_id_blocks(h.ranks, {total, h.ranks.size}, h.particles.id,
                                    h.particles.owned_count(), v, per);
}

std::vector<double> reference_in_id_order(const sph::Hydro& h, long total) {
  std::vector<double> x;
  owned_values(h, h.particles.X, 3)(x);
  return in_id_order(h, total, x, 3);
}

long particles_total(const sph::Hydro& h) {
  return h.ranks.sum(static_cast<long>(h.particles.owned_count()));
}

/// Whether every index of `v` names one of `n` particles.
bool names_particles(const std::vector<int>& v, std::size_t n) {
  return std::all_of(v.begin(), v.end(),
                     [n](int j) { return j >= 0 && static_cast<std::size_t>(j) < n; });
}

/// Whether a neighbour list read back is whole over `n` particles: offsets from 0 to the
/// partners' count that never go down, no more rows than particles, partners that are particles.
bool whole_list(const neighbors::PairList& l, std::size_t n) {
  return !l.offset.empty() && l.offset.front() == 0 &&
         l.offset.back() == static_cast<long>(l.partner.size()) &&
         std::is_sorted(l.offset.begin(), l.offset.end()) &&
         l.offset.size() <= n + 1 && names_particles(l.partner, n);
}

/// A state read back at the lengths it was kept (SphRun::restore) must be whole: every kept
/// per-particle array of as many particles as the positions, the owned ones among them adding up
/// over the ranks to the run's, and the neighbour lists, material groups, remote ghosts and
/// mirror images naming particles there are. A forged or mixed checkpoint is refused so, before
/// a step reads past an array.
void check_whole(const sph::Hydro& h, long particles) {
  const std::size_t n = h.particles.X.size() / 3;
  const auto same_count = [n](const char* part) {
    return [n, part](const particles::FieldInfo& f, const auto& a) {
      if (a.size() != n * static_cast<std::size_t>(f.components))
        io::refuse_checkpoint("'sph." + std::string(part) + f.name + "' holds " +
                              std::to_string(a.size() / f.components) + " particles, the " +
                              "positions " + std::to_string(n) + " (a damaged checkpoint)");
    };
  };
  particles::for_each_kept(h.particles, same_count("particles."));
  particles::for_each_kept(h.fields, same_count("fields."));
  const long owned = h.particles.owned_count();
  const long total = h.ranks.sum(owned);
  if (total != particles)
    io::refuse_checkpoint("the checkpoint's ranks own " + std::to_string(total) +
                          " particles, this run has " + std::to_string(particles));
  const std::size_t ghosts = n - static_cast<std::size_t>(std::max(0L, owned));
  const std::size_t images = h.ghost_source.size(); // the last particles, after the remote ones
  const std::size_t sources = n - images;            // images mirror owned or remote particles
  if (owned < 0 || static_cast<std::size_t>(owned) > n || h.remote < 0 ||
      static_cast<std::size_t>(h.remote) > ghosts ||
      h.remote_owner.size() != static_cast<std::size_t>(h.remote) ||
      static_cast<std::size_t>(h.remote) + images != ghosts ||
      h.ghost_planes.size() != images || !names_particles(h.ghost_source, sources) ||
      !whole_list(h.neighbours.pairs, n) || !whole_list(h.neighbours.half_pairs, n) ||
      !names_particles(h.groups.members, n))
    io::refuse_checkpoint("the checkpoint's particles, ghosts, neighbour lists and material "
                          "groups do not go together (a damaged checkpoint)");
}

} // namespace

SphRun::SphRun(sph::Hydro& h, const spec::SphSpec& spec, io::OutputDirectory* out,
               SphRunResult& result)
    : h_(h), spec_(spec), r_(result), gauges_(gauge_points(spec), h.particles.X,
                                              h.particles.owned_count(), h.ranks, h.particles.id),
      fields_(out, "fields", reference_in_id_order(h, particles_total(h)),
              field_slice(h, particles_total(h))) {
  const particles::ParticleSet& P = h_.particles;
  const sph::ParticleFields& F = h_.fields;
  r_.particles = static_cast<int>(particles_total(h_));
  r_.mpi_ranks = h_.ranks.size;
  r_.smallest_dt = std::numeric_limits<double>::infinity();
  const char* axes[] = {"x", "y", "z"};
  gauges_.record("pressure", [&F](int i) { return F.p[i]; });
  gauges_.record("density", [&F](int i) { return F.rho[i]; });
  gauges_.record("von_mises", [this](int i) { return von_mises(i); });
  gauges_.record("yield_stress", [&P, &F, &h](int i) {
    return materials::current_yield(h.materials[P.material[i]].strength, F.p[i], F.alpha[i],
                                    F.damage[i], F.strain_rate[i]);
  });
  gauges_.record("plastic_strain", [&F](int i) { return F.alpha[i]; });
  for (int d = 0; d < spec.dimension; ++d)
    gauges_.record(std::string("v") + axes[d], [&P, d](int i) { return P.v[3 * i + d]; });
  for (int d = 0; d < spec.dimension; ++d)
    gauges_.record(std::string("u") + axes[d], [&P, d](int i) { return P.u[3 * i + d]; });
  gauges_.track("pressure", [&F](int i) { return F.p[i]; });
  gauges_.track("speed", [&P](int i) {
    return std::sqrt(P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] +
                     P.v[3 * i + 2] * P.v[3 * i + 2]);
  });
  std::vector<std::string> H = {
      "time",         "step",          "dt",           "kinetic_energy", "internal_energy",
      "total_energy", "external_work", "energy_error", "max_pressure"};
  for (const std::string& c : gauges_.columns()) H.push_back(c);
  r_.history = io::History(H);
  e0_ = sph::energies(h_).total();

  // The body's particles only (ghosts, copies and mirror images, are not written): the arrays
  // the registries name for output, then the quantities derived from them.
  const auto written = [this](const particles::FieldInfo& f, const auto& a) {
    if (f.output) field(f.output, f.components, owned_values(h_, a, f.components));
  };
  P.for_each_field(written);
  F.for_each_field(written);
  field("von_mises", 1, [this](std::vector<double>& mises) {
    mises.resize(h_.particles.owned_count());
    for (int i = 0; i < h_.particles.owned_count(); ++i) mises[i] = von_mises(i);
  });
  stress_fields();
  // Each frame shows the deformed body, as LS-DYNA's d3plot does: the particles at X + u.
  fields_.positions([this](std::vector<double>& out) {
    const particles::ParticleSet& q = h_.particles;
    std::vector<double> x(3 * static_cast<std::size_t>(q.owned_count()));
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = q.X[k] + q.u[k];
    out = in_id_order(h_, r_.particles, x, 3);
  });
}

void SphRun::stress_fields() {
  // The Cauchy stress sigma = S - p I (tension positive), named as the implicit analyses name
  // theirs; sigma_zz of plane strain too. Voigt order of S: xx yy zz yz xz xy.
  struct Component {
    const char* name;
    int k;
  };
  std::vector<Component> components{
      {"stress_xx", 0}, {"stress_yy", 1}, {"stress_zz", 2}, {"stress_xy", 5}};
  if (h_.dim == 3) components.insert(components.end(), {{"stress_yz", 3}, {"stress_xz", 4}});
  for (const Component& c : components)
    field(c.name, 1, [this, k = c.k](std::vector<double>& out) {
      const sph::ParticleFields& F = h_.fields;
      out.resize(h_.particles.owned_count());
      for (int i = 0; i < h_.particles.owned_count(); ++i)
        out[i] = F.S[6 * static_cast<std::size_t>(i) + k] - (k < 3 ? F.p[i] : 0.0);
    });
}

void SphRun::field(std::string name, int per, io::FieldOutput::Fill owned) {
  const long total = r_.particles;
  io::FieldOutput::Fill fill = [this, per, total, owned](std::vector<double>& out) {
    std::vector<double> mine;
    owned(mine);
    out = in_id_order(h_, total, mine, per);
  };
  if (per == 3)
    fields_.vector(std::move(name), std::move(fill));
  else
    fields_.scalar(std::move(name), std::move(fill));
}

void SphRun::advance(double dt, bool) {
  sph::advance(h_, dt);
  // Particles may have moved to another rank: each gauge follows its particle there.
  if (!h_.ranks.serial()) gauges_.follow(h_.particles.id, h_.particles.owned_count());
}

double SphRun::max_pressure() const {
  const std::vector<double>& p = h_.fields.p;
  double most = -std::numeric_limits<double>::infinity(); // a rank may hold no particle
  for (const int i : h_.particles.owned()) most = std::max(most, p[i]);
  return h_.ranks.max(most);
}

double SphRun::von_mises(int i) const {
  // Von Mises stress of the deviator: sqrt(3/2 S:S).
  const double* si = &h_.fields.S[6 * static_cast<std::size_t>(i)];
  return std::sqrt(1.5 * (si[0] * si[0] + si[1] * si[1] + si[2] * si[2] +
                          2.0 * (si[3] * si[3] + si[4] * si[4] + si[5] * si[5])));
}

namespace {
constexpr double kCollapse = 1e-6; // the smallest CFL step a run takes, over its first
} // namespace

bool SphRun::time_step(double remaining, double& dt, std::string& why) {
  int limiting = -1;
  const double stable = sph::stable_step(h_, &limiting);
  if (!(stable > 0.0) || !std::isfinite(stable)) {
    why = detail::concat("no finite CFL step at t = ", h_.particles.time, " (step ",
                         h_.particles.step, ")");
    return false;
  }
  dt = dt_ = std::min(stable, remaining);
  if (h_.particles.step == 0) r_.first_dt = dt;
  if (stable < r_.smallest_dt) {
    // The particle that set it, from the rank that holds it.
    double at[6] = {0, 0, 0, 0, 0, 0}; // x, y, z, h, c, id
    if (limiting >= 0) {
      const Vec3 x = h_.particles.position(limiting);
      const double mine[6] = {x.x(),
                              x.y(),
                              x.z(),
                              h_.fields.h[limiting],
                              h_.fields.c[limiting],
                              static_cast<double>(h_.particles.id[limiting])};
      std::copy(mine, mine + 6, at);
    }
    h_.ranks.sum(at, 6);
    r_.smallest_dt = stable;
    r_.dt_limit =
        detail::concat("CFL step ", stable, " (Courant ", spec_.numerics.courant, ") set at step ",
                       h_.particles.step, " by particle ", static_cast<long>(at[5]), " at (", at[0],
                       ", ", at[1], ", ", at[2], "), h ", at[3], ", c ", at[4]);
  }
  // A step a million times below the first is a collapsing state, not a slow run: it would take
  // a million times the steps planned (LS-DYNA stops the same way at its DTMIN).
  if (h_.particles.step > 0 && stable < kCollapse * r_.first_dt) {
    why = detail::concat("the CFL step fell to ", stable, ", below ", kCollapse, " of the first (",
                         r_.first_dt, "), at t = ", h_.particles.time, " (step ", h_.particles.step,
                         "): ", r_.dt_limit, "; check the regions' density, energy and velocity");
    return false;
  }
  return true;
}

void SphRun::track() {
  r_.peak_pressure = std::max(r_.peak_pressure, max_pressure());
  gauges_.update_maxima();
}

int SphRun::nonfinite() const {
  const particles::ParticleSet& P = h_.particles;
  double first = std::numeric_limits<double>::infinity(); // the lowest id over every rank
  for (const int i : P.owned())
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(P.u[3 * i + d]) || !std::isfinite(P.v[3 * i + d]))
        first = std::min(first, static_cast<double>(P.id[i]));
  first = h_.ranks.min(first);
  return std::isfinite(first) ? static_cast<int>(first) : -1;
}

Vec3 SphRun::position(int id) const {
  const particles::ParticleSet& P = h_.particles;
  Vec3 x(0.0, 0.0, 0.0);
  for (const int i : P.owned())
    if (P.id[i] == id) x = P.reference(i);
  h_.ranks.sum(x.data(), 3); // from the one rank that owns it
  return x;
}

std::string SphRun::advice() const {
  return detail::concat("the last step ", dt_, " (Courant ", spec_.numerics.courant,
                        ") may be too large");
}

void SphRun::record() {
  const sph::Energies E = sph::energies(h_);
  const double work = h_.ranks.sum(h_.external_work); // each rank's loads' part
  // The balance: total energy against its start plus the work of the loads.
  const double err =
      std::abs(E.total() - e0_ - work) / std::max({std::abs(e0_), std::abs(work), E.kinetic,
                                                   std::abs(E.internal), energy_scale_, 1e-300});
  r_.energy_error = std::max(r_.energy_error, err);
  std::vector<double> row{h_.particles.time,
                          static_cast<double>(h_.particles.step),
                          dt_,
                          E.kinetic,
                          E.internal,
                          E.total(),
                          work,
                          err,
                          max_pressure()};
  gauges_.append_to(row);
  r_.history.append(std::move(row));
}

std::string SphRun::progress() const {
  char text[64];
  std::snprintf(text, sizeof text, "dt %.4g, max pressure %.4g", dt_, max_pressure());
  return text;
}

template <class Visit> void SphRun::for_each_state(const Visit& visit) {
  io::visit_count(visit, "particles", r_.particles);
  h_.for_each_state(visit / "sph");
  visit("e0", e0_), visit("dt", dt_), visit("first_dt", r_.first_dt);
  visit("smallest_dt", r_.smallest_dt), visit("dt_limit", r_.dt_limit);
  visit("peak_pressure", r_.peak_pressure), visit("energy_error", r_.energy_error);
  gauges_.for_each_state(visit / "gauges");
  fields_.for_each_state(visit / "fields");
  r_.history.for_each_state(visit / "history");
}

void SphRun::save(io::Checkpoints& checkpoints, const io::Saver& save) {
  fields_.split(checkpoints.part("fields", checkpoints.generation()));
  for_each_state(save);
}

void SphRun::restore(const io::Loader& load) {
  // A rank's particles and neighbour lists are those it held at the checkpoint, not at set-up
  // (particles move between ranks, lists change): the particle count checks the discretisation.
  io::Loader moved = load;
  moved.resizes = true;
  for_each_state(moved);
  check_whole(h_, r_.particles);
  sph::resume_distribution(h_);
}

void SphRun::finish(const LoopReport& loop) {
  fields_.close();
  r_.status = loop.status;
  r_.stop_reason = loop.stop_reason;
  r_.timer.add("stepping", loop.seconds);
  r_.steps = h_.particles.step;
  r_.neighbour_rebuilds = h_.neighbours.rebuilds;
  const distribution::Ranks& ranks = h_.ranks;
  r_.neighbour_seconds = ranks.max(h_.neighbours.seconds);
  r_.neighbour_pairs = ranks.sum(static_cast<long>(h_.neighbours.pairs.partner.size()));
  const auto bytes = [](const neighbors::PairList& l) {
    return static_cast<long>(l.partner.size() * sizeof(int) + l.offset.size() * sizeof(long));
  };
  r_.neighbour_list_bytes = ranks.sum(bytes(h_.neighbours.pairs) + bytes(h_.neighbours.half_pairs));
  r_.remote_ghosts = ranks.sum(static_cast<long>(h_.remote));
  r_.remote_ghosts_largest = static_cast<long>(ranks.max(static_cast<double>(h_.remote)));
  r_.migrated = ranks.sum(h_.migrated);
  r_.bounded_h = {ranks.sum(h_.bounded_h.at_min), ranks.sum(h_.bounded_h.at_max)};
  r_.gauge_maxima = gauges_.maxima();
  r_.particle_steps_per_second =
      loop.seconds > 0.0 ? static_cast<double>(r_.particles) * loop.steps_timed / loop.seconds
                         : 0.0;
  if (!loop.completed()) log::info("stopped: ", r_.stop_reason);
  log::info("done: ", r_.steps, " steps, ", r_.neighbour_rebuilds, " neighbour-list builds (",
            loop.seconds > 0.0 ? 100.0 * r_.neighbour_seconds / loop.seconds : 0.0,
            "% of the stepping time), ", r_.particle_steps_per_second,
            " particle steps/s, largest energy error ", r_.energy_error);
  log::info("smallest step: ", r_.dt_limit);
}

} // namespace mf::explicit_dynamics
