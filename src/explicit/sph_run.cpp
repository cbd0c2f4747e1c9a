#include "meshfree/explicit/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::explicit_dynamics {

namespace {

std::vector<GaugePoint> gauge_points(const io::SphSpec& s) {
  std::vector<GaugePoint> g;
  for (const auto& p : s.gauges) g.push_back({p.name, Vec3(p.at[0], p.at[1], p.at[2])});
  return g;
}

/// The reference positions of the owned particles, where the fields are written.
std::vector<double> reference_of(const sph::Hydro& h) {
  const std::vector<double>& X = h.particles.X;
  return {X.begin(), X.begin() + 3 * static_cast<std::ptrdiff_t>(h.particles.owned_count())};
}

} // namespace

SphRun::SphRun(sph::Hydro& h, const io::SphSpec& spec, io::OutputDirectory* out,
               SphRunResult& result)
    : h_(h), spec_(spec), r_(result), n_(h.particles.owned_count()),
      gauges_(gauge_points(spec), h.particles.X, n_), fields_(out, "fields", reference_of(h)) {
  const particles::ParticleSet& P = h_.particles;
  const sph::ParticleFields& F = h_.fields;
  r_.particles = n_;
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

  // The body's particles only (mirror images beyond them are not written).
  fields_.vector("displacement", P.u);
  fields_.vector("velocity", P.v);
  fields_.scalar("density", F.rho);
  fields_.scalar("pressure", F.p);
  fields_.scalar("specific_energy", F.e);
  fields_.scalar("smoothing_length", F.h);
  fields_.scalar("von_mises", [this](std::vector<double>& mises) {
    mises.resize(n_);
    for (int i = 0; i < n_; ++i) mises[i] = von_mises(i);
  });
  fields_.scalar("plastic_strain", F.alpha);
  fields_.scalar("damage", F.damage);
  fields_.scalar("failed", F.failed);
  fields_.scalar("material", P.material);
}

double SphRun::max_pressure() const {
  return *std::max_element(h_.fields.p.begin(), h_.fields.p.end());
}

double SphRun::von_mises(int i) const {
  // Von Mises stress of the deviator: sqrt(3/2 S:S).
  const double* si = &h_.fields.S[6 * static_cast<std::size_t>(i)];
  return std::sqrt(1.5 * (si[0] * si[0] + si[1] * si[1] + si[2] * si[2] +
                          2.0 * (si[3] * si[3] + si[4] * si[4] + si[5] * si[5])));
}

bool SphRun::time_step(double remaining, double& dt, std::string& why) {
  int limiting = -1;
  const double stable = sph::stable_step(h_, &limiting);
  if (!(stable > 0.0) || !std::isfinite(stable)) {
    why = detail::concat("no finite CFL step at t = ", h_.particles.time, " (step ",
                         h_.particles.step, ", particle ", limiting, ")");
    return false;
  }
  dt = dt_ = std::min(stable, remaining);
  if (h_.particles.step == 0) r_.first_dt = dt;
  if (stable < r_.smallest_dt) {
    const Vec3 x = h_.particles.position(limiting);
    const sph::ParticleFields& F = h_.fields;
    r_.smallest_dt = stable;
    r_.dt_limit =
        detail::concat("CFL step ", stable, " (Courant ", spec_.numerics.courant, ") set at step ",
                       h_.particles.step, " by particle ", limiting, " at (", x.x(), ", ", x.y(),
                       ", ", x.z(), "), h ", F.h[limiting], ", c ", F.c[limiting]);
  }
  return true;
}

void SphRun::track() {
  r_.peak_pressure = std::max(r_.peak_pressure, max_pressure());
  gauges_.update_maxima();
}

int SphRun::nonfinite() const {
  const particles::ParticleSet& P = h_.particles;
  for (const int i : P.owned())
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(P.u[3 * i + d]) || !std::isfinite(P.v[3 * i + d])) return i;
  return -1;
}

std::string SphRun::advice() const {
  return detail::concat("the last step ", dt_, " (Courant ", spec_.numerics.courant,
                        ") may be too large");
}

void SphRun::record() {
  const sph::Energies E = sph::energies(h_);
  // The balance: total energy against its start plus the work of the loads.
  const double err = std::abs(E.total() - e0_ - h_.external_work) /
                     std::max({std::abs(e0_), std::abs(h_.external_work), E.kinetic,
                               std::abs(E.internal), 1e-300});
  r_.energy_error = std::max(r_.energy_error, err);
  std::vector<double> row{h_.particles.time,
                          static_cast<double>(h_.particles.step),
                          dt_,
                          E.kinetic,
                          E.internal,
                          E.total(),
                          h_.external_work,
                          err,
                          max_pressure()};
  gauges_.append_to(row);
  r_.history.append(std::move(row));
}

std::string SphRun::progress() const {
  return detail::concat("dt ", dt_, ", max pressure ", max_pressure());
}

void SphRun::finish(const LoopReport& loop) {
  fields_.close();
  r_.status = loop.status;
  r_.stop_reason = loop.stop_reason;
  r_.timer.add("stepping", loop.seconds);
  r_.steps = h_.particles.step;
  r_.neighbour_rebuilds = h_.rebuilds;
  r_.neighbour_seconds = h_.neighbour_seconds;
  r_.neighbour_pairs = static_cast<long>(h_.pairs.partner.size());
  r_.neighbour_list_bytes = static_cast<long>(h_.pairs.partner.size() * sizeof(int) +
                                              h_.pairs.offset.size() * sizeof(long));
  r_.gauge_maxima = gauges_.maxima();
  r_.particle_steps_per_second =
      loop.seconds > 0.0 ? static_cast<double>(n_) * h_.particles.step / loop.seconds : 0.0;
  if (!loop.completed()) log::info("stopped: ", r_.stop_reason);
  log::info("done: ", r_.steps, " steps, ", r_.neighbour_rebuilds, " neighbour-list builds (",
            loop.seconds > 0.0 ? 100.0 * r_.neighbour_seconds / loop.seconds : 0.0,
            "% of the stepping time), ", r_.particle_steps_per_second,
            " particle steps/s, largest energy error ", r_.energy_error);
  log::info("smallest step: ", r_.dt_limit);
}

} // namespace mf::explicit_dynamics
