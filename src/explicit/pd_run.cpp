#include "meshfree/explicit/pd_run.hpp"
#include "meshfree/core/error.hpp"
#include "meshfree/core/log.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::explicit_dynamics {

namespace {

std::vector<GaugePoint> gauge_points(const spec::PdSpec& s) {
  std::vector<GaugePoint> g;
  for (const auto& p : s.output.gauges) g.push_back({p.name, p.at});
  return g;
}

std::vector<double> owned_positions(const particles::ParticleSet& p) {
  return {p.X.begin(), p.X.begin() + 3 * static_cast<std::size_t>(p.owned_count())};
}

/// Where this rank's particles go in the one field file: its block of ids.
io::PointSlice field_slice(const PdSetup& setup) {
  const distribution::Ranks& ranks = setup.model.halo.ranks();
  if (ranks.serial()) return {};
  return {ranks.comm, static_cast<std::size_t>(setup.first_id),
          static_cast<std::size_t>(setup.particles_total)};
}

} // namespace

PdRun::PdRun(PdSetup& setup, const spec::PdSpec& spec, io::OutputDirectory* out,
             PdRunResult& result)
    : setup_(setup), spec_(spec), r_(result),
      gauges_(gauge_points(spec), setup.model.particles.X, setup.model.particles.owned_count(),
              setup.model.halo.ranks()),
      fields_(out, "fields", owned_positions(setup.model.particles), field_slice(setup)) {
  pd::Model& m = setup_.model;
  const particles::ParticleSet& p = m.particles;
  count_body();
  if (spec_.relaxation) relax_at_start();
  contact_ = !setup_.impactors.empty() || setup_.short_range;
  last_ = pd::accelerate(m, setup_.state, setup_.loading, interactions(), true);
  e0_ = pd::kinetic_energy(m) + last_.strain_energy;
  if (contact_) e0_ += last_.contact_energy + impactor_energy();
  broken_ = last_.broken;
  gauge_motion();
  r_.history = io::History(history_columns());

  fields_.scalar("damage", phi_); // derived: pd::damage at each write
  p.for_each_field([this](const particles::FieldInfo& f, const auto& a) {
    if (f.output) f.components == 3 ? fields_.vector(f.output, a) : fields_.scalar(f.output, a);
  });
  // Each frame shows the deformed body, as LS-DYNA's d3plot does: the particles at X + u.
  fields_.positions([this](std::vector<double>& x) {
    const particles::ParticleSet& q = setup_.model.particles;
    x.resize(3 * static_cast<std::size_t>(q.owned_count()));
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = q.X[k] + q.u[k];
  });
}

void PdRun::count_body() {
  const pd::Model& m = setup_.model;
  r_.particles = static_cast<int>(setup_.particles_total);
  r_.bonds = ranks().sum(m.bonds.directed) / 2; // a bond between two ranks is held by both
  // The halo: each ghost is 24 bytes of displacement received before every force evaluation.
  const long ghosts = m.particles.ghosts().size();
  r_.ghosts = ranks().sum(ghosts);
  r_.ghosts_largest = static_cast<long>(ranks().max(static_cast<double>(ghosts)));
  const double directed = std::max(1.0, static_cast<double>(m.bonds.directed));
  const long stored = std::max(1L, m.bonds.stored());
  r_.bond_bytes_steady =
      m.bonds.bytes(static_cast<int>(setup_.state.plastic.size() / stored)) / directed;
  r_.bond_bytes_peak = std::max(m.bonds.peak_bytes / directed, r_.bond_bytes_steady);
  r_.dt = setup_.dt;
  r_.dt_limit = setup_.dt_limit;
}

void PdRun::relax_at_start() {
  MF_REQUIRE(ranks().serial(),
             "relaxation: the static relaxation before the first step runs on "
             "one MPI rank (",
             ranks().size, " given)");
  PhaseTimer::Scope scope(r_.timer, "relaxation");
  pd::Model& m = setup_.model;
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

void PdRun::gauge_motion() {
  const particles::ParticleSet& p = setup_.model.particles;
  const char* axes[] = {"x", "y", "z"};
  const int dims = setup_.model.plane() ? 2 : 3;
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
}

std::vector<std::string> PdRun::history_columns() const {
  const char* axes[] = {"x", "y", "z"};
  const int dims = setup_.model.plane() ? 2 : 3;
  std::vector<std::string> H = {"time",          "step",          "kinetic_energy",
                                "strain_energy", "external_work", "energy_balance",
                                "broken_bonds",  "max_damage"};
  // With contact the balance also holds the contact potential energy, the free impactors'
  // kinetic energy, the work of prescribed impactors' drives and what kinematic contact
  // dissipates, and the strain energy broken bonds took with them: E = KE + SE + contact +
  // impactors' KE, E - E0 - W_ext - W_drive + D_contact + D_fracture = 0.
  if (contact_)
    H.insert(H.end(), {"contact_energy", "impactor_kinetic_energy", "impactor_work",
                       "contact_dissipation", "fracture_energy"});
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
  return H;
}

void PdRun::advance(double dt, bool history_due) {
  last_ = pd::advance(setup_.model, setup_.state, setup_.loading, interactions(), dt, history_due);
  fracture_ += last_.fracture_energy - last_.fracture_work;
  last_has_energy_ = history_due;
  work_ += last_.external_work;
  broken_ += last_.broken;
}

int PdRun::nonfinite() const {
  const particles::ParticleSet& p = setup_.model.particles;
  const std::vector<double>& u = p.u;
  double first = std::numeric_limits<double>::infinity(); // the lowest id over every rank
  for (int i : p.owned())
    if (!std::isfinite(u[3 * i]) || !std::isfinite(u[3 * i + 1]) || !std::isfinite(u[3 * i + 2])) {
      first = static_cast<double>(p.id[i]);
      break;
    }
  first = ranks().min(first);
  return std::isfinite(first) ? static_cast<int>(first) : -1;
}

Vec3 PdRun::position(int id) const {
  const particles::ParticleSet& p = setup_.model.particles;
  const long i = id - setup_.first_id;
  Vec3 x(0.0, 0.0, 0.0);
  if (i >= 0 && i < p.owned_count()) x = p.reference(static_cast<int>(i));
  ranks().sum(x.data(), 3); // from the one rank that owns it
  return x;
}

std::string PdRun::overflowing_load() const {
  const pd::Model& m = setup_.model;
  const double dt = setup_.dt, t = time();
  for (const pd::BodyLoad& l : setup_.loading.loads) {
    const double f = setup_.loading.factor(l.function, t);
    for (std::size_t k = 0; k < l.particles.size(); ++k)
      for (int d = 0; d < 3; ++d) {
        const double b = l.density_of(k, d) * f;
        const double move = std::abs(b) / m.particles.density[l.particles[k]] * dt * dt;
        if (!std::isfinite(b) || !(move < 1e6 * m.spacing))
          return detail::concat("the load '", l.name, "' is ", b, " per unit volume at t = ", t,
                                ", which moves a particle ", move, " in one step of ", dt,
                                ": is its value (or its function's) meant?");
      }
  }
  return "";
}

std::string PdRun::advice() const {
  const std::string load = overflowing_load();
  if (!load.empty()) return load;
  return detail::concat("the time step ", setup_.dt, " (", setup_.dt_limit,
                        ") is probably too large");
}

void PdRun::record() {
  pd::Model& m = setup_.model;
  const particles::ParticleSet& p = m.particles;
  // A row between history instants (the last one) needs the strain energy of the state.
  if (!last_has_energy_) {
    last_ = pd::accelerate(m, setup_.state, setup_.loading, interactions(), true);
    fracture_ += last_.fracture_energy;
  }
  last_has_energy_ = true;
  const double strain_energy = last_.strain_energy;
  pd::damage(m, setup_.state, phi_);
  const double kinetic = pd::kinetic_energy(m);
  double max_damage = 0.0;
  for (int i : p.owned()) max_damage = std::max(max_damage, phi_[i]);
  std::vector<double> row{p.time,
                          static_cast<double>(p.step),
                          kinetic,
                          strain_energy,
                          work_,
                          kinetic + strain_energy - e0_ - work_,
                          static_cast<double>(broken_ / 2),
                          ranks().max(max_damage)};
  if (contact_) {
    double drive = 0.0, dissipated = 0.0;
    for (const auto& imp : setup_.impactors) drive += imp.work, dissipated += imp.dissipated;
    const double moving = impactor_energy();
    // The strain energy of the last evaluation still holds the bonds it broke.
    const double fracture = fracture_ - last_.fracture_energy;
    row[5] = kinetic + strain_energy + last_.contact_energy + moving - e0_ - work_ - drive +
             dissipated + fracture;
    row.insert(row.end(), {last_.contact_energy, moving, drive, dissipated, fracture});
  }
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
    // The farthest over every rank (the lowest rank on a tie, as one rank's first).
    const int holder = ranks().rank_of_min(-reach);
    reach = ranks().max(reach);
    ranks().broadcast(tip.data(), 3, holder);
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

template <class Visit> void PdRun::for_each_state(const Visit& visit) {
  io::visit_count(visit, "particles", setup_.particles_total);
  particles::ParticleSet& p = setup_.model.particles;
  // The particles keep their rank: what the set-up made, it makes again at restart.
  particles::for_each_kept(p, visit / "particles", particles::kSetUp);
  visit("particles.time", p.time), visit("particles.step", p.step);
  pd::BondState& b = setup_.state;
  visit("bonds.intact", b.intact), visit("bonds.plastic", b.plastic);
  visit("bonds.s0", b.s0.committed), visit("bonds.s0_trial", b.s0.trial);
  io::visit_list(visit, "impactors", setup_.impactors,
                 [](const auto& at, pd::Impactor& imp) { imp.for_each_state(at); });
  if (setup_.short_range) setup_.short_range->for_each_state(visit / "short_range");
  // The bonds broken in the last step vary in number as the run goes.
  fracture_account_.for_each_state((visit / "fracture_account").resizing());
  visit("last.broken", last_.broken), visit("last.strain_energy", last_.strain_energy);
  visit("last.external_work", last_.external_work);
  visit("last.contact_energy", last_.contact_energy);
  visit("last.fracture_energy", last_.fracture_energy);
  visit("last.fracture_work", last_.fracture_work);
  visit("last_has_energy", last_has_energy_), visit("fracture", fracture_);
  visit("e0", e0_), visit("work", work_), visit("broken", broken_);
  visit("max_damage", r_.max_damage);
  gauges_.for_each_state(visit / "gauges");
  fields_.for_each_state(visit / "fields");
  r_.history.for_each_state(visit / "history");
}

void PdRun::save(io::Checkpoints& checkpoints, const io::Saver& save) {
  fields_.split(checkpoints.part("fields", checkpoints.generation()));
  for_each_state(save);
}

void PdRun::restore(const io::Loader& load) {
  // Plastic stretches and the LAMMPS rule's s0 are kept by a run whose laws use them only (else
  // empty, and the loader would take any length): the set-up says which.
  pd::BondState& b = setup_.state;
  const std::size_t plastic = b.plastic.size(), s0 = b.s0.committed.size();
  const std::size_t s0_trial = b.s0.trial.size();
  for_each_state(load);
  if (b.plastic.size() != plastic)
    io::refuse_checkpoint("the checkpoint holds " + std::to_string(b.plastic.size()) +
                          " plastic stretches, this run has " + std::to_string(plastic));
  if (b.s0.committed.size() != s0 || b.s0.trial.size() != s0_trial)
    io::refuse_checkpoint("the checkpoint holds " + std::to_string(b.s0.committed.size()) + " and " +
                          std::to_string(b.s0.trial.size()) + " critical stretches s0, this run " +
                          "has " + std::to_string(s0) + " and " + std::to_string(s0_trial));
  // Lists of particles, read back at the length kept, must name particles of this run.
  const int n = setup_.model.particles.size();
  const bool pairs = !setup_.short_range || setup_.short_range->consistent();
  const bool gauges = std::all_of(gauges_.particles().begin(), gauges_.particles().end(),
                                  [n](int i) { return i >= -1 && i < n; });
  if (!pairs || !gauges || !fracture_account_.consistent(setup_.model.particles.owned_count()))
    io::refuse_checkpoint(std::string("the checkpoint's ") +
                          (!pairs    ? "contact pairs"
                           : !gauges ? "gauges"
                                     : "broken bonds") +
                          " name particles this run does not have (a damaged checkpoint)");
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
  r_.bond_updates_per_second = loop.advance_seconds > 0.0
                                   ? static_cast<double>(setup_.model.bonds.directed) *
                                         loop.steps_timed / loop.advance_seconds
                                   : 0.0;
  double emax = 0.0, drift = 0.0;
  for (const auto& row : r_.history.rows()) {
    emax = std::max({emax, row[2] + row[3], std::abs(row[4])});
    if (contact_) // contact energy, impactors' kinetic energy, drive work, dissipations
      emax = std::max({emax, row[2] + row[3] + row[8] + row[9], std::abs(row[10]),
                       std::abs(row[11]), std::abs(row[12])});
    drift = std::max(drift, std::abs(row[5]));
  }
  r_.energy_drift = emax > 0.0 ? drift / emax : 0.0;
  if (!loop.completed()) log::info("stopped: ", r_.stop_reason);
  log::info("done: ", loop.steps, " steps, ", r_.broken_bonds, " broken bonds, ",
            r_.bond_updates_per_second, " bond evaluations/s, energy balance ", r_.energy_drift);
}

} // namespace mf::explicit_dynamics
