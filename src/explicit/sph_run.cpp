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

} // namespace

SphRun::SphRun(sph::Hydro& h, const io::SphSpec& spec, io::OutputDirectory* out,
               SphRunResult& result)
    : h_(h), spec_(spec), r_(result), n_(h.particles.size()), x0_(h.particles.x),
      gauges_(gauge_points(spec), x0_, n_), fields_(out, "fields", x0_) {
  const sph::Particles& P = h_.particles;
  r_.particles = n_;
  r_.smallest_dt = std::numeric_limits<double>::infinity();
  const char* axes[] = {"x", "y", "z"};
  gauges_.record("pressure", [&P](int i) { return P.p[i]; });
  gauges_.record("density", [&P](int i) { return P.rho[i]; });
  gauges_.record("von_mises", [this](int i) { return von_mises(i); });
  gauges_.record("yield_stress", [&P, &h](int i) {
    return materials::current_yield(h.materials[P.material[i]].strength, P.p[i], P.alpha[i],
                                    P.damage[i], P.strain_rate[i]);
  });
  gauges_.record("plastic_strain", [&P](int i) { return P.alpha[i]; });
  for (int d = 0; d < spec.dimension; ++d)
    gauges_.record(std::string("v") + axes[d], [&P, d](int i) { return P.v[3 * i + d]; });
  for (int d = 0; d < spec.dimension; ++d)
    gauges_.record(std::string("u") + axes[d],
                   [&P, this, d](int i) { return P.x[3 * i + d] - x0_[3 * i + d]; });
  gauges_.track("pressure", [&P](int i) { return P.p[i]; });
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
  fields_.vector("displacement", [this](std::vector<double>& u) {
    u.assign(h_.particles.x.begin(), h_.particles.x.begin() + 3 * static_cast<std::ptrdiff_t>(n_));
    for (std::size_t k = 0; k < u.size(); ++k) u[k] -= x0_[k];
  });
  fields_.vector("velocity", P.v);
  fields_.scalar("density", P.rho);
  fields_.scalar("pressure", P.p);
  fields_.scalar("specific_energy", P.e);
  fields_.scalar("smoothing_length", P.h);
  fields_.scalar("von_mises", [this](std::vector<double>& mises) {
    mises.resize(n_);
    for (int i = 0; i < n_; ++i) mises[i] = von_mises(i);
  });
  fields_.scalar("plastic_strain", P.alpha);
  fields_.scalar("damage", P.damage);
  fields_.scalar("failed", P.failed);
  fields_.scalar("material", P.material);
}

double SphRun::max_pressure() const {
  return *std::max_element(h_.particles.p.begin(), h_.particles.p.end());
}

double SphRun::von_mises(int i) const {
  // Von Mises stress of the deviator: sqrt(3/2 S:S).
  const double* si = &h_.particles.S[6 * static_cast<std::size_t>(i)];
  return std::sqrt(1.5 * (si[0] * si[0] + si[1] * si[1] + si[2] * si[2] +
                          2.0 * (si[3] * si[3] + si[4] * si[4] + si[5] * si[5])));
}

bool SphRun::time_step(double remaining, double& dt, std::string& why) {
  int limiting = -1;
  const double stable = sph::stable_step(h_, &limiting);
  if (!(stable > 0.0) || !std::isfinite(stable)) {
    why = detail::concat("no finite CFL step at t = ", h_.time, " (step ", h_.step, ", particle ",
                         limiting, ")");
    return false;
  }
  dt = dt_ = std::min(stable, remaining);
  if (h_.step == 0) r_.first_dt = dt;
  if (stable < r_.smallest_dt) {
    const sph::Particles& P = h_.particles;
    r_.smallest_dt = stable;
    r_.dt_limit = detail::concat(
        "CFL step ", stable, " (Courant ", spec_.numerics.courant, ") set at step ", h_.step,
        " by particle ", limiting, " at (", P.x[3 * limiting], ", ", P.x[3 * limiting + 1], ", ",
        P.x[3 * limiting + 2], "), h ", P.h[limiting], ", c ", P.c[limiting]);
  }
  return true;
}

void SphRun::track() {
  r_.peak_pressure = std::max(r_.peak_pressure, max_pressure());
  gauges_.update_maxima();
}

int SphRun::nonfinite() const {
  const sph::Particles& P = h_.particles;
  for (int i = 0; i < n_; ++i)
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(P.x[3 * i + d]) || !std::isfinite(P.v[3 * i + d])) return i;
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
  std::vector<double> row{h_.time,
                          static_cast<double>(h_.step),
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
  r_.steps = h_.step;
  r_.neighbour_rebuilds = h_.rebuilds;
  r_.gauge_maxima = gauges_.maxima();
  r_.particle_steps_per_second =
      loop.seconds > 0.0 ? static_cast<double>(n_) * h_.step / loop.seconds : 0.0;
  if (!loop.completed()) log::info("stopped: ", r_.stop_reason);
  log::info("done: ", r_.steps, " steps, ", r_.neighbour_rebuilds, " neighbour-list builds, ",
            r_.particle_steps_per_second, " particle steps/s, largest energy error ",
            r_.energy_error);
  log::info("smallest step: ", r_.dt_limit);
}

} // namespace mf::explicit_dynamics
