#include "meshfree/explicit/pd_run.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include <algorithm>
#include <cmath>

namespace mf::explicit_dynamics {

namespace {

std::vector<GaugePoint> gauge_points(const io::PdSpec& s) {
  std::vector<GaugePoint> g;
  for (const auto& p : s.gauges) g.push_back({p.name, p.at});
  return g;
}

} // namespace

PdRun::PdRun(PdSetup& setup, const io::PdSpec& spec, io::OutputDirectory* out, PdRunResult& result)
    : setup_(setup), spec_(spec), r_(result),
      gauges_(gauge_points(spec), setup.model.particles.X, setup.model.particles.size()),
      fields_(out, "fields", setup.model.particles.X) {
  pd::Model& m = setup_.model;
  const particles::ParticleSet& p = m.particles;
  r_.particles = p.size();
  r_.bonds = m.bonds.pairs();
  const double directed = std::max(1.0, static_cast<double>(m.bonds.directed));
  r_.bond_bytes_steady = m.bonds.bytes(!setup_.state.plastic.empty()) / directed;
  r_.bond_bytes_peak = std::max(m.bonds.peak_bytes / directed, r_.bond_bytes_steady);
  r_.dt = setup_.dt;
  r_.dt_limit = setup_.dt_limit;
  if (spec_.relaxation) {
    PhaseTimer::Scope scope(r_.timer, "relaxation");
    const std::vector<double> v0 = m.particles.v;
    pd::RelaxSettings settings;
    settings.tolerance = spec_.relaxation->tolerance;
    settings.max_iterations = spec_.relaxation->max_iterations;
    r_.relaxation = pd::relax(m, setup_.state, setup_.loading, settings);
    m.particles.v = v0;
    const pd::RelaxReport& x = *r_.relaxation;
    MF_REQUIRE(x.converged, "relaxation: no static equilibrium within ", x.iterations,
               " iterations (residual ratio ", x.residual_ratio, " against the tolerance ",
               settings.tolerance, "); raise relaxation.max_iterations or check the supports");
    log::info("relaxation: static equilibrium under the loads at t = 0 in ", x.iterations,
              " iterations (residual ratio ", x.residual_ratio, "), ", x.seconds, " s");
  }
  last_ = pd::accelerate(m, setup_.state, setup_.loading, true);
  e0_ = pd::kinetic_energy(m) + last_.strain_energy;
  broken_ = last_.broken;

  const char* axes[] = {"x", "y", "z"};
  const int dims = m.plane() ? 2 : 3;
  for (const auto* field : {&p.u, &p.v, &p.a})
    for (int d = 0; d < dims; ++d) {
      const std::string name = std::string(field == &p.u   ? "u"
                                           : field == &p.v ? "v"
                                                           : "a") +
                               axes[d];
      const auto value = [field, d](int i) { return (*field)[3 * i + d]; };
      gauges_.record(name, value);
      gauges_.track(name, value);
    }
  std::vector<std::string> H = {"time",          "step",          "kinetic_energy",
                                "strain_energy", "external_work", "energy_balance",
                                "broken_bonds",  "max_damage"};
  for (const auto& imp : setup_.impactors) { // a fixed support records only its force
    if (!imp.fixed) {
      for (int d = 0; d < dims; ++d) H.push_back(imp.name + "_position_" + axes[d]);
      for (int d = 0; d < dims; ++d) H.push_back(imp.name + "_velocity_" + axes[d]);
    }
    for (int d = 0; d < dims; ++d) H.push_back(imp.name + "_force_" + axes[d]);
  }
  for (const std::string& c : gauges_.columns()) H.push_back(c);
  if (spec_.crack.enabled)
    H.insert(H.end(), {"crack_tip_x", "crack_tip_y", "crack_tip_z", "crack_length"});
  r_.history = io::History(H);

  fields_.vector("displacement", p.u);
  fields_.vector("velocity", p.v);
  fields_.scalar("damage", phi_);
  fields_.scalar("material", p.material);
}

void PdRun::advance(double dt, bool history_due) {
  last_ =
      pd::advance(setup_.model, setup_.state, setup_.loading, setup_.impactors, dt, history_due);
  last_has_energy_ = history_due;
  work_ += last_.external_work;
  broken_ += last_.broken;
}

int PdRun::nonfinite() const {
  const std::vector<double>& u = setup_.model.particles.u;
  for (std::size_t k = 0; k < u.size(); k += 3)
    if (!std::isfinite(u[k]) || !std::isfinite(u[k + 1]) || !std::isfinite(u[k + 2]))
      return static_cast<int>(k / 3);
  return -1;
}

std::string PdRun::advice() const {
  return detail::concat("the time step ", setup_.dt, " (", setup_.dt_limit,
                        ") is probably too large");
}

void PdRun::record() {
  pd::Model& m = setup_.model;
  const particles::ParticleSet& p = m.particles;
  // A row between history instants (the last one) needs the strain energy of the state.
  const double strain_energy =
      last_has_energy_ ? last_.strain_energy
                       : pd::accelerate(m, setup_.state, setup_.loading, true).strain_energy;
  pd::damage(m, setup_.state, phi_);
  const double kinetic = pd::kinetic_energy(m);
  std::vector<double> row{p.time,
                          static_cast<double>(p.step),
                          kinetic,
                          strain_energy,
                          work_,
                          kinetic + strain_energy - e0_ - work_,
                          static_cast<double>(broken_ / 2),
                          *std::max_element(phi_.begin(), phi_.end())};
  const int dims = m.plane() ? 2 : 3;
  for (const auto& imp : setup_.impactors) {
    if (!imp.fixed) {
      for (int d = 0; d < dims; ++d) row.push_back(imp.position(d));
      for (int d = 0; d < dims; ++d) row.push_back(imp.velocity(d));
    }
    for (int d = 0; d < dims; ++d) row.push_back(imp.contact_force(d));
  }
  gauges_.append_to(row);
  if (spec_.crack.enabled) {
    // The crack tip: the damaged particle farthest along the tracking direction from the
    // origin (pd::damage at or above the threshold marks a crack, paper 001: 0.38 for delta = 3
    // dx).
    double reach = 0.0;
    Vec3 tip = spec_.crack.origin;
    for (int i : p.owned()) {
      if (phi_[i] < spec_.crack.threshold) continue;
      const double along = (p.reference(i) - spec_.crack.origin).dot(spec_.crack.direction);
      if (along > reach) reach = along, tip = p.reference(i);
    }
    row.insert(row.end(), {tip.x(), tip.y(), tip.z(), reach});
  }
  r_.max_damage = row[7];
  r_.history.append(std::move(row));
}

void PdRun::write_fields() {
  if (!fields_.active()) return;
  pd::damage(setup_.model, setup_.state, phi_);
  fields_.write(time());
}

void PdRun::finish(const LoopReport& loop) {
  fields_.close();
  r_.steps = loop.steps;
  r_.status = loop.status;
  r_.stop_reason = loop.stop_reason;
  r_.broken_bonds = broken_ / 2;
  r_.timer.add("stepping", loop.seconds);
  r_.gauge_maxima = gauges_.maxima();
  // Bond evaluations counted as directed bonds, as LAMMPS's 'total # of bonds' (the half bond
  // layout computes each pair once for both of its ends).
  r_.bond_updates_per_second =
      loop.advance_seconds > 0.0
          ? static_cast<double>(setup_.model.bonds.directed) * loop.steps / loop.advance_seconds
          : 0.0;
  double emax = 0.0, drift = 0.0;
  for (const auto& row : r_.history.rows()) {
    emax = std::max({emax, row[2] + row[3], std::abs(row[4])});
    drift = std::max(drift, std::abs(row[5]));
  }
  r_.energy_drift = emax > 0.0 ? drift / emax : 0.0;
  if (!loop.completed()) log::info("stopped: ", r_.stop_reason);
  log::info("done: ", loop.steps, " steps, ", r_.broken_bonds, " broken bonds, ",
            r_.bond_updates_per_second, " bond evaluations/s, energy balance ", r_.energy_drift);
}

} // namespace mf::explicit_dynamics
