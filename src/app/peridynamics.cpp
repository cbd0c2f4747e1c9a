#include "meshfree/app/peridynamics.hpp"
#include "meshfree/core/log.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <omp.h>

namespace mf::app {

namespace {

using io::Vec3d;
using Clock = std::chrono::steady_clock;

/// Cell-centred lattice of spacing dx over the body: a 3D box, or the 2D domain's bounding box
/// with the points the domain contains.
pd::Particles lattice(const io::ProblemSpec& spec) {
  const io::PdSpec& s = *spec.pd;
  const double dx = s.spacing;
  pd::Particles p;
  const bool solid = s.dimension == materials::PdDimension::Solid3D;
  Vec3d lo, hi;
  if (solid) {
    lo = s.box->lo;
    hi = s.box->hi;
  } else {
    const BoundingBox b = spec.domain.bounds();
    lo = Vec3d(b.lo.x(), b.lo.y(), 0.0);
    hi = Vec3d(b.hi.x(), b.hi.y(), 0.0);
  }
  long count[3];
  for (int d = 0; d < 3; ++d)
    count[d] = std::max(1L, static_cast<long>(std::lround((hi(d) - lo(d)) / dx)));
  if (!solid) count[2] = 1;
  const double estimate = static_cast<double>(count[0]) * count[1] * count[2];
  MF_REQUIRE(estimate <= 5e7, "discretisation.spacing: ", dx, " gives about ", estimate,
             " particles; one run is meant for at most 5e7");
  const double volume = solid ? dx * dx * dx : dx * dx * s.thickness;
  for (long k = 0; k < count[2]; ++k)
    for (long j = 0; j < count[1]; ++j)
      for (long i = 0; i < count[0]; ++i) {
        const Vec3d x(lo.x() + (i + 0.5) * dx, lo.y() + (j + 0.5) * dx,
                      solid ? lo.z() + (k + 0.5) * dx : 0.0);
        if (!solid && !spec.domain.contains(Vec2(x.x(), x.y()))) continue;
        bool removed = false;
        for (const io::Box3& b : s.removed) removed = removed || b.contains(x, 1e-9 * dx);
        if (removed) continue;
        int mat = 0;
        for (const io::PdRegion& r : s.regions)
          if (r.box.contains(x, 1e-9 * dx))
            for (std::size_t m = 0; m < s.materials.size(); ++m)
              if (s.materials[m].name == r.material) mat = static_cast<int>(m);
        p.add(x, volume, s.materials[mat].density, mat);
      }
  MF_REQUIRE(p.size() > 0, "discretisation.spacing: no particle lies in the body");
  return p;
}

/// The bond law of one material: micromodulus (from E, the bulk modulus or given), critical
/// stretch (from G0, given, or none), micro-plastic yield stretch and the LAMMPS alpha.
materials::BondLaw material_law(const io::PdSpec& s, const io::PdMaterial& m, double delta) {
  materials::BondLaw law;
  law.c = m.micromodulus > 0.0   ? m.micromodulus
          : m.bulk_modulus > 0.0 ? materials::pd_micromodulus_from_bulk(m.bulk_modulus, delta)
                                 : materials::pd_micromodulus(s.dimension, m.E, delta, s.thickness);
  if (m.critical_stretch > 0.0) {
    law.critical_stretch = m.critical_stretch;
  } else if (m.fracture_energy > 0.0) {
    law.critical_stretch =
        m.bulk_modulus > 0.0 || m.micromodulus > 0.0
            ? materials::pd_critical_stretch_from_c(law.c, m.fracture_energy, delta)
            : materials::pd_critical_stretch(s.dimension, m.E, m.fracture_energy, delta);
  }
  law.yield_stretch = m.yield_stretch;
  law.alpha = m.alpha;
  return law;
}

/// Laws of every material pair: a material's own law, an interface's base law scaled by its
/// factors, or (pairs with no interface) the law of the pair's softer material.
pd::LawTable law_table(const io::PdSpec& s, double delta) {
  pd::LawTable t;
  const int n = static_cast<int>(s.materials.size());
  t.materials = n;
  for (const auto& m : s.materials) t.laws.push_back(material_law(s, m, delta));
  t.law_of.assign(n * n, 0);
  const auto index = [&](const std::string& name) {
    for (int k = 0; k < n; ++k)
      if (s.materials[k].name == name) return k;
    return 0;
  };
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      t.law_of[a * n + b] = a == b ? a : (t.laws[a].c <= t.laws[b].c ? a : b);
  for (const io::PdInterface& f : s.interfaces) {
    materials::BondLaw law = t.laws[index(f.base)];
    law.yield_stretch *= f.yield_stretch_factor;
    law.critical_stretch *= f.critical_stretch_factor;
    t.laws.push_back(law);
    const int a = index(f.a), b = index(f.b), k = static_cast<int>(t.laws.size()) - 1;
    t.law_of[a * n + b] = t.law_of[b * n + a] = k;
  }
  return t;
}

std::vector<int> particles_in(const pd::Particles& p, const std::optional<io::Box3>& box,
                              double tol) {
  std::vector<int> out;
  for (int i = 0; i < p.size(); ++i)
    if (!box || box->contains(p.position(i), tol)) out.push_back(i);
  return out;
}

/// Traction t on a layer of particles as a body force: b = t A / (volume of the layer). A is
/// given, or is the layer's volume over its thickness normal to the loaded face (the thinnest
/// extent of the layer, one spacing per particle row), so that b = t / thickness.
Vec3d traction_density(const io::PdCondition& c, const pd::Particles& p,
                       const std::vector<int>& group, double dx, int dims) {
  double volume = 0.0;
  Vec3d lo = p.position(group.front()), hi = lo;
  for (int i : group) {
    volume += p.volume[i];
    lo = lo.cwiseMin(p.position(i));
    hi = hi.cwiseMax(p.position(i));
  }
  if (c.area > 0.0) return c.value * c.area / volume;
  double thickness = std::numeric_limits<double>::infinity();
  for (int d = 0; d < dims; ++d) thickness = std::min(thickness, hi(d) - lo(d) + dx);
  return c.value / thickness;
}

/// A blast on a face: each particle of the layer gets the Friedlander history of its distance
/// and angle of incidence; the force per volume of a unit pressure is -n / (layer thickness).
/// In a plane model the charge lies in the plane and distances are measured in it.
std::vector<loads::Friedlander> blast_pulses(const io::PdCondition& c, const pd::Particles& p,
                                             const std::vector<int>& group, double dx, int dims,
                                             Vec3d& density) {
  io::PdCondition unit = c;
  unit.value = -c.blast.normal;
  unit.area = 0.0;
  density = traction_density(unit, p, group, dx, dims);
  const loads::Burst burst =
      c.blast.surface_burst ? loads::Burst::HemisphericalSurface : loads::Burst::SphericalFreeAir;
  std::vector<loads::Friedlander> out;
  out.reserve(group.size());
  for (int i : group) {
    const Vec3d ray = p.position(i) - c.blast.charge;
    const double r = ray.norm();
    loads::BlastParameters b;
    try {
      b = loads::kingery_bulmash(burst, c.blast.tnt_mass, r);
    } catch (const Error& e) {
      fail(c.key_path, ".blast: particle at (", p.position(i).x(), ", ", p.position(i).y(), ", ",
           p.position(i).z(), "): ", e.what());
    }
    out.push_back(loads::blast_pulse(b, -c.blast.normal.dot(ray) / r));
  }
  return out;
}

} // namespace

PdSetup build_pd_setup(const io::ProblemSpec& spec, PhaseTimer& timer) {
  const io::PdSpec& s = *spec.pd;
  PdSetup out;
  pd::Model& m = out.model;
  m.dimension = s.dimension;
  m.thickness = s.thickness;
  m.spacing = s.spacing;
  m.horizon = s.horizon_factor * s.spacing;
  for (const auto& mat : s.materials) m.material_names.push_back(mat.name);
  {
    PhaseTimer::Scope scope(timer, "particles");
    m.particles = lattice(spec);
  }
  {
    PhaseTimer::Scope scope(timer, "bonds");
    const pd::VolumeCorrection correction =
        s.volume_correction == "exact"    ? pd::VolumeCorrection::Exact
        : s.volume_correction == "linear" ? pd::VolumeCorrection::Linear
                                          : pd::VolumeCorrection::None;
    pd::build_bonds(m, law_table(s, m.horizon), correction);
    if (s.surface_correction) pd::apply_surface_correction(m);
    std::vector<pd::PreCrack> cracks;
    for (const auto& c : s.cracks) cracks.push_back({c.a, c.b, c.c});
    out.state = pd::initial_state(m, cracks);
  }
  const pd::Particles& p = m.particles;
  const double tol = 1e-6 * s.spacing;
  for (const auto& f : s.functions) out.loading.functions.push_back(f.f);
  for (const io::PdCondition& c : s.conditions) {
    const std::vector<int> group = particles_in(p, c.box, tol);
    MF_REQUIRE(!group.empty(), c.key_path, ".box: selects no particle");
    if (c.kind == io::PdCondition::Kind::Displacement ||
        c.kind == io::PdCondition::Kind::Velocity) {
      pd::Constraint k;
      k.name = c.name;
      k.particles = group;
      k.velocity = c.kind == io::PdCondition::Kind::Velocity;
      for (int d = 0; d < 3; ++d) k.fixed[d] = c.fixed[d], k.value[d] = c.value(d);
      k.function = c.function;
      out.loading.constraints.push_back(k);
    } else {
      pd::BodyLoad load;
      load.name = c.name;
      load.particles = group;
      load.density = c.kind == io::PdCondition::Kind::Traction
                         ? traction_density(c, p, group, s.spacing, m.plane() ? 2 : 3)
                         : c.value;
      load.function = c.function;
      if (c.kind == io::PdCondition::Kind::Blast)
        load.pulses = blast_pulses(c, p, group, s.spacing, m.plane() ? 2 : 3, load.density);
      out.loading.loads.push_back(load);
    }
  }
  out.initial_velocity.assign(3 * static_cast<std::size_t>(p.size()), 0.0);
  for (const auto& iv : s.initial_velocities)
    for (int i : particles_in(p, iv.box, tol))
      for (int d = 0; d < 3; ++d) out.initial_velocity[3 * i + d] = iv.value(d);
  for (const io::PdImpactor& k : s.impactors) {
    pd::Impactor imp;
    imp.name = k.name;
    imp.shape = k.sphere ? pd::Impactor::Shape::Sphere : pd::Impactor::Shape::Flat;
    imp.radius = k.radius;
    imp.half_size = k.half_size;
    imp.mass = k.mass;
    imp.fixed = k.fixed;
    imp.position = k.position;
    imp.velocity = k.velocity;
    if (!k.sphere) imp.direction = k.velocity.normalized();
    out.impactors.push_back(imp);
  }
  for (const io::PdGauge& g : s.gauges) {
    int best = 0;
    double d2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < p.size(); ++i) {
      const double e = (p.position(i) - g.at).squaredNorm();
      if (e < d2) d2 = e, best = i;
    }
    out.gauge_particle.push_back(best);
  }
  // The time step: the Silling-Askari bound times the safety factor, one step per load sample
  // when a table is finer, or the step asked for (never above the bound).
  int limiting = -1;
  const double stable = pd::stable_time_step(m, &limiting);
  MF_REQUIRE(std::isfinite(stable), "peridynamics: no particle has a bond; is the horizon "
                                    "(discretisation.horizon) smaller than the spacing?");
  out.dt = s.safety * stable;
  const Vec3d where = p.position(limiting);
  out.dt_limit = detail::concat("stable step ", stable, " (Silling & Askari 2005) times safety ",
                                s.safety, ", set by the particle at (", where.x(), ", ", where.y(),
                                ", ", where.z(), ")");
  for (const auto& f : s.functions)
    if (f.f.kind == loads::TimeFunction::Kind::Table && f.f.sample_step < out.dt) {
      out.dt = f.f.sample_step;
      out.dt_limit = "one step per sample of the load table '" + f.name + "' (" +
                     detail::concat(f.f.sample_step) + ")";
    }
  if (s.dt > 0.0) {
    MF_REQUIRE(s.dt <= stable, "time.dt: ", s.dt, " exceeds the stable time step ", stable,
               " (Silling & Askari 2005); velocity Verlet would diverge");
    if (s.dt < out.dt) {
      out.dt = s.dt;
      out.dt_limit = "time.dt";
    }
  }
  return out;
}

PdResult run_peridynamics(const io::ProblemSpec& spec, io::OutputDirectory* out) {
  const io::PdSpec& s = *spec.pd;
  PdResult R;
  PdSetup setup = build_pd_setup(spec, R.timer);
  pd::Model& m = setup.model;
  const pd::Particles& p = m.particles;
  const int n = p.size();
  R.particles = n;
  R.bonds = m.bonds.count() / 2;
  R.dt = setup.dt;
  R.dt_limit = setup.dt_limit;
  log::info("peridynamics: ", n, " particles, ", R.bonds, " bonds, horizon ", m.horizon, " (",
            s.horizon_factor, " spacings), ", m.laws.size(), " bond law(s)");
  for (std::size_t k = 0; k < m.laws.size(); ++k)
    log::info("  law ", k, ": c ", m.laws[k].c, ", critical stretch ", m.laws[k].critical_stretch,
              m.laws[k].plastic() ? detail::concat(", yield stretch ", m.laws[k].yield_stretch)
                                  : "");
  log::info("time step ", R.dt, ": ", R.dt_limit);
  for (const pd::BodyLoad& load : setup.loading.loads) {
    if (load.pulses.empty()) continue;
    const auto [lo, hi] = std::minmax_element(
        load.pulses.begin(), load.pulses.end(),
        [](const loads::Friedlander& a, const loads::Friedlander& b) { return a.peak < b.peak; });
    log::info("blast '", load.name, "' on ", load.pulses.size(), " particles: peak ", lo->peak,
              "..", hi->peak, " Pa, arrival ", hi->arrival, "..", lo->arrival, " s, duration ",
              hi->duration, "..", lo->duration, " s, impulse ", lo->impulse(), "..", hi->impulse(),
              " Pa s");
  }

  pd::Motion q(n);
  q.v = setup.initial_velocity;
  pd::StepReport first = pd::accelerate(m, setup.state, q, setup.loading, true);
  const double e0 = pd::kinetic_energy(m, q) + first.strain_energy;

  // History columns.
  const bool plane = m.plane();
  const char* axes[] = {"x", "y", "z"};
  const int dims = plane ? 2 : 3;
  std::vector<std::string> H = {"time",          "step",          "kinetic_energy",
                                "strain_energy", "external_work", "energy_balance",
                                "broken_bonds",  "max_damage"};
  for (const auto& imp : setup.impactors) { // a fixed support records only its force
    if (!imp.fixed) {
      for (int d = 0; d < dims; ++d) H.push_back(imp.name + "_position_" + axes[d]);
      for (int d = 0; d < dims; ++d) H.push_back(imp.name + "_velocity_" + axes[d]);
    }
    for (int d = 0; d < dims; ++d) H.push_back(imp.name + "_force_" + axes[d]);
  }
  for (const auto& g : s.gauges)
    for (const char* what : {"u", "v", "a"})
      for (int d = 0; d < dims; ++d) H.push_back(g.name + "_" + what + axes[d]);
  if (s.crack.enabled)
    H.insert(H.end(), {"crack_tip_x", "crack_tip_y", "crack_tip_z", "crack_length"});
  R.history = io::History(H);

  double work = 0.0;
  long broken = first.broken;
  std::vector<double> phi;
  const auto record = [&](double strain_energy) {
    pd::damage(m, setup.state, phi);
    const double kinetic = pd::kinetic_energy(m, q);
    std::vector<double> row{q.time,
                            static_cast<double>(q.step),
                            kinetic,
                            strain_energy,
                            work,
                            kinetic + strain_energy - e0 - work,
                            static_cast<double>(broken / 2),
                            *std::max_element(phi.begin(), phi.end())};
    for (const auto& imp : setup.impactors) {
      if (!imp.fixed) {
        for (int d = 0; d < dims; ++d) row.push_back(imp.position(d));
        for (int d = 0; d < dims; ++d) row.push_back(imp.velocity(d));
      }
      for (int d = 0; d < dims; ++d) row.push_back(imp.contact_force(d));
    }
    for (int i : setup.gauge_particle)
      for (const std::vector<double>* field : {&q.u, &q.v, &q.a})
        for (int d = 0; d < dims; ++d) row.push_back((*field)[3 * i + d]);
    if (s.crack.enabled) {
      // The crack tip: the damaged particle farthest along the tracking direction from the
      // origin (damage at or above the threshold marks a crack, paper 001: 0.38 for delta = 3 dx).
      double reach = 0.0;
      Vec3d tip = s.crack.origin;
      for (int i = 0; i < n; ++i) {
        if (phi[i] < s.crack.threshold) continue;
        const double along = (p.position(i) - s.crack.origin).dot(s.crack.direction);
        if (along > reach) reach = along, tip = p.position(i);
      }
      row.insert(row.end(), {tip.x(), tip.y(), tip.z(), reach});
    }
    R.max_damage = row[7];
    R.history.append(std::move(row));
  };

  io::FieldOutput fields(out, "fields", p.x);
  fields.vector("displacement", q.u);
  fields.vector("velocity", q.v);
  fields.scalar("damage", phi);
  fields.scalar("material", p.material);
  const auto write_fields = [&]() { fields.write(q.time); };

  // Gauge maxima over every step.
  for (const auto& g : s.gauges)
    for (const char* what : {"u", "v", "a"})
      for (int d = 0; d < dims; ++d)
        R.gauge_maxima.emplace_back(g.name + "_" + what + axes[d], 0.0);
  const auto track_gauges = [&]() {
    std::size_t k = 0;
    for (int i : setup.gauge_particle)
      for (const std::vector<double>* field : {&q.u, &q.v, &q.a})
        for (int d = 0; d < dims; ++d, ++k)
          R.gauge_maxima[k].second =
              std::max(R.gauge_maxima[k].second, std::abs((*field)[3 * i + d]));
  };
  track_gauges();
  record(first.strain_energy);
  write_fields();
  double next_history = s.history_interval, next_fields = s.fields_interval;
  double next_progress = 0.1 * s.end_time;
  const auto t_start = Clock::now();
  double bond_seconds = 0.0;
  long steps = 0;
  while (q.time < s.end_time * (1.0 - 1e-12)) {
    const double dt = std::min(setup.dt, s.end_time - q.time);
    const bool history_due = s.history_interval <= 0.0 || q.time + dt >= next_history * (1 - 1e-12);
    const auto t0 = Clock::now();
    const pd::StepReport r =
        pd::advance(m, setup.state, q, setup.loading, setup.impactors, dt, history_due);
    bond_seconds += seconds_since(t0);
    ++steps;
    track_gauges();
    work += r.external_work;
    broken += r.broken;
    if (history_due) {
      for (std::size_t k = 0; k < q.u.size(); k += 3)
        if (!std::isfinite(q.u[k]) || !std::isfinite(q.u[k + 1]) || !std::isfinite(q.u[k + 2])) {
          const Vec3d x = p.position(static_cast<int>(k / 3));
          R.status = "failed";
          R.stop_reason = detail::concat("the motion became non-finite at step ", q.step,
                                         " (t = ", q.time, ") at the particle at (", x.x(), ", ",
                                         x.y(), ", ", x.z(), "); the time step ", setup.dt, " (",
                                         setup.dt_limit, ") is probably too large");
          break;
        }
      if (R.status != "completed") break;
      record(r.strain_energy);
      while (next_history <= q.time * (1 + 1e-12) && s.history_interval > 0.0)
        next_history += s.history_interval;
    }
    if (s.fields_interval > 0.0 && q.time >= next_fields * (1 - 1e-12)) {
      if (!history_due) pd::damage(m, setup.state, phi);
      write_fields();
      while (next_fields <= q.time * (1 + 1e-12)) next_fields += s.fields_interval;
    }
    if (q.time >= next_progress) {
      log::info("  t = ", q.time, " (", static_cast<int>(std::lround(100 * q.time / s.end_time)),
                "%), step ", q.step, ", broken bonds ", broken / 2, ", ", seconds_since(t_start),
                " s");
      next_progress += 0.1 * s.end_time;
    }
  }
  R.steps = steps;
  R.broken_bonds = broken / 2;
  R.timer.add("stepping", seconds_since(t_start));
  // Each step evaluates every intact bond from both of its ends.
  R.bond_updates_per_second =
      bond_seconds > 0.0 ? 2.0 * static_cast<double>(R.bonds) * steps / bond_seconds : 0.0;
  if (R.status == "completed") {
    if (R.history.empty() || R.history.last()[0] < q.time) {
      const pd::StepReport last = pd::accelerate(m, setup.state, q, setup.loading, true);
      record(last.strain_energy);
    }
    pd::damage(m, setup.state, phi);
    write_fields();
  }
  fields.close();
  double emax = 0.0, drift = 0.0;
  for (const auto& row : R.history.rows()) {
    emax = std::max({emax, row[2] + row[3], std::abs(row[4])});
    drift = std::max(drift, std::abs(row[5]));
  }
  R.energy_drift = emax > 0.0 ? drift / emax : 0.0;
  log::info("done: ", steps, " steps, ", R.broken_bonds, " broken bonds, ",
            R.bond_updates_per_second, " bond evaluations/s, energy balance ", R.energy_drift);
  return R;
}

void write_pd_outputs(const io::ProblemSpec& spec, const PdResult& r, io::OutputDirectory& out) {
  r.history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "peridynamics", ""});
  summary.set_status(r.status, r.stop_reason);
  summary.set("openmp_threads", omp_get_max_threads());
  summary.section("counts")
      .set("particles", r.particles)
      .set("bonds", r.bonds)
      .set("steps", r.steps);
  summary.section("time_step").set("dt", r.dt).set("limited_by", r.dt_limit);
  io::Json& results = summary.section("results");
  results.set("broken_bonds", r.broken_bonds)
      .set("max_damage", r.max_damage)
      .set("energy_balance_relative", r.energy_drift)
      .set("bond_evaluations_per_second", r.bond_updates_per_second);
  // Largest magnitudes of every recorded history column (gauges, impactor, crack).
  io::Json maxima;
  for (std::size_t c = 2; c < r.history.columns().size(); ++c)
    maxima.set(r.history.columns()[c], r.history.max_abs(c));
  results.set("max_abs", maxima);
  io::Json gauges;
  for (const auto& [name, v] : r.gauge_maxima) gauges.set(name, v);
  results.set("gauge_max_abs_every_step", gauges);
  summary.write(out, r.timer);
}

} // namespace mf::app
