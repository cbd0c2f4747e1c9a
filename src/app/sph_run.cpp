#include "meshfree/app/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/sph/detonation.hpp"
#include "meshfree/sph/state.hpp"
#include "meshfree/sph/step.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

namespace mf::app {

namespace {

using Clock = std::chrono::steady_clock;

/// Whether a free particle lies in the box [lo, hi].
bool free_in_box(const sph::Particles& P, int i, const std::array<double, 3>& lo,
                 const std::array<double, 3>& hi) {
  if (P.fixed[i]) return false;
  for (int d = 0; d < 3; ++d)
    if (P.x[3 * i + d] < lo[d] - 1e-9 || P.x[3 * i + d] > hi[d] + 1e-9) return false;
  return true;
}

/// The face area of a particle in a surface layer one particle thick: V / spacing.
double face_area(const sph::Particles& P, int i, int dim) {
  const double volume = P.mass[i] / P.rho_ref[i];
  return volume / std::pow(volume, 1.0 / dim);
}

int material_index(const io::SphSpec& s, const std::string& name) {
  for (std::size_t k = 0; k < s.materials.size(); ++k)
    if (s.materials[k].name == name) return static_cast<int>(k);
  return -1;
}

} // namespace

sph::Hydro build_sph(const io::SphSpec& s) {
  sph::Hydro h;
  h.materials = s.materials;
  h.settings = s.settings;
  sph::Particles& P = h.particles;
  P.dim = s.dimension;
  for (const io::SphBlock& b : s.blocks) {
    const int mat = material_index(s, b.material);
    const auto add = [&](const double x[3], double volume) {
      if (b.inside) {
        const double dx = x[0] - b.inside->center[0], dy = x[1] - b.inside->center[1];
        if (dx * dx + dy * dy > b.inside->radius * b.inside->radius) return;
      }
      for (const io::SphCircle& c : b.holes) {
        const double dx = x[0] - c.center[0], dy = x[1] - c.center[1];
        if (dx * dx + dy * dy < c.radius * c.radius) return;
      }
      const double spacing = std::pow(volume, 1.0 / s.dimension);
      P.add(x, b.density * volume, b.density, b.energy, s.smoothing * spacing, mat, b.fixed);
      for (int d = 0; d < 3; ++d) P.v[P.v.size() - 3 + d] = b.velocity[d];
    };
    if (b.is_ring) {
      // Rings of particles at radii r_k, each with round(2 pi r_k / spacing) particles whose
      // areas add up to the annulus exactly.
      const double thickness = b.ring.radius - b.ring_inner_radius;
      const int layers = std::max(1, static_cast<int>(std::lround(thickness / b.spacing)));
      const double dr = thickness / layers;
      for (int k = 0; k < layers; ++k) {
        const double r = b.ring_inner_radius + (k + 0.5) * dr;
        const int around = std::max(3, static_cast<int>(std::lround(2.0 * M_PI * r / b.spacing)));
        for (int a = 0; a < around; ++a) {
          const double theta = 2.0 * M_PI * (a + 0.5) / around;
          const double x[3] = {b.ring.center[0] + r * std::cos(theta),
                               b.ring.center[1] + r * std::sin(theta), 0.0};
          add(x, 2.0 * M_PI * r * dr / around);
        }
      }
      continue;
    }
    int count[3] = {1, 1, 1};
    for (int d = 0; d < s.dimension; ++d)
      count[d] = std::max(1, static_cast<int>(std::lround((b.hi[d] - b.lo[d]) / b.spacing)));
    double step[3];
    for (int d = 0; d < 3; ++d) step[d] = d < s.dimension ? (b.hi[d] - b.lo[d]) / count[d] : 0.0;
    double volume = 1.0;
    for (int d = 0; d < s.dimension; ++d) volume *= step[d];
    for (int k = 0; k < count[2]; ++k)
      for (int j = 0; j < count[1]; ++j)
        for (int i = 0; i < count[0]; ++i) {
          const int idx[3] = {i, j, k};
          double x[3] = {0, 0, 0};
          for (int d = 0; d < s.dimension; ++d) x[d] = b.lo[d] + (idx[d] + 0.5) * step[d];
          add(x, volume);
        }
  }
  for (const io::SphBlastLoad& l : s.loads) {
    // Each particle of the layer carries its face area V / spacing and the Friedlander history
    // of its own distance and angle of incidence (loads/blast.hpp).
    sph::SurfaceLoad load;
    load.name = l.name;
    for (int d = 0; d < 3; ++d) load.direction[d] = -l.normal[d];
    const loads::Burst burst =
        l.surface_burst ? loads::Burst::HemisphericalSurface : loads::Burst::SphericalFreeAir;
    for (int i = 0; i < P.size(); ++i) {
      if (!free_in_box(P, i, l.lo, l.hi)) continue;
      double ray[3], r = 0.0, cosine = 0.0;
      for (int d = 0; d < 3; ++d) ray[d] = P.x[3 * i + d] - l.charge[d], r += ray[d] * ray[d];
      r = std::sqrt(r);
      for (int d = 0; d < 3; ++d) cosine -= l.normal[d] * ray[d] / r;
      loads::BlastParameters b;
      try {
        // near_field: clamp loads particles nearer than the fits reach with the values at the
        // smallest scaled distance the fits cover (the crater region is not modelled).
        const double r_min = loads::kingery_bulmash_range(burst).first * std::cbrt(l.tnt_mass);
        b = loads::kingery_bulmash(burst, l.tnt_mass, l.clamp_below_range ? std::max(r, r_min) : r);
      } catch (const Error& e) {
        fail(l.key_path, ".blast: particle at (", P.x[3 * i], ", ", P.x[3 * i + 1], ", ",
             P.x[3 * i + 2], "): ", e.what());
      }
      load.particles.push_back(i);
      load.area.push_back(face_area(P, i, s.dimension));
      load.pulses.push_back(loads::blast_pulse(b, cosine));
    }
    MF_REQUIRE(!load.particles.empty(), l.key_path, ".box: selects no free particle");
    h.loads.push_back(load);
  }
  h.symmetry = s.symmetry;
  for (std::size_t q = 0; q < s.symmetry.size(); ++q) {
    // The body must lie on one side of each symmetry plane.
    const sph::SymmetryPlane& m = s.symmetry[q];
    int below = 0, above = 0;
    for (int i = 0; i < P.size(); ++i) (P.x[3 * i + m.axis] < m.at ? below : above) += 1;
    MF_REQUIRE(below == 0 || above == 0, "symmetry[", q, "]: the plane ", "xyz"[m.axis], " = ",
               m.at, " cuts the body (", below, " particles below it, ", above, " above)");
  }
  if (s.detonation_normal)
    sph::light_from_plane(h, s.detonation_point->data(), s.detonation_normal->data());
  else if (s.detonation_point)
    sph::light_from_point(h, s.detonation_point->data());
  sph::update_state(h);
  for (const io::SphTransmitting& t : s.transmitting) {
    // Lysmer dashpots with the particle's initial impedances rho c_L and rho c_s.
    sph::TransmittingBoundary b;
    b.name = t.name;
    for (int d = 0; d < 3; ++d) b.normal[d] = t.normal[d];
    for (int i = 0; i < P.size(); ++i) {
      if (!free_in_box(P, i, t.lo, t.hi)) continue;
      b.particles.push_back(i);
      b.area.push_back(face_area(P, i, s.dimension));
      b.normal_impedance.push_back(P.rho[i] * P.c[i]);
      b.shear_impedance.push_back(std::sqrt(
          P.rho[i] * materials::shear_modulus(h.materials[P.material[i]].strength, P.rho[i])));
    }
    MF_REQUIRE(!b.particles.empty(), t.key_path, ".box: selects no free particle");
    h.transmitting.push_back(b);
  }
  return h;
}

SphResult run_sph(const io::ProblemSpec& spec, io::OutputDirectory* out) {
  const io::SphSpec& s = *spec.sph;
  SphResult R;
  sph::Hydro h;
  {
    PhaseTimer::Scope scope(R.timer, "particles");
    h = build_sph(s);
  }
  sph::Particles& P = h.particles;
  const int n = P.size(), dims = s.dimension;
  R.particles = n;
  log::info("sph: ", n, " particles in ", dims, "D, ", s.materials.size(), " material(s)",
            s.detonation_point ? ", detonation lit" : "");
  const std::vector<double> x0 = P.x;

  // Lagrangian gauges: the particle nearest each point at the start.
  std::vector<int> gauge;
  for (const io::SphGauge& g : s.gauges) {
    int best = 0;
    double d2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      double e = 0.0;
      for (int d = 0; d < 3; ++d) e += (P.x[3 * i + d] - g.at[d]) * (P.x[3 * i + d] - g.at[d]);
      if (e < d2) d2 = e, best = i;
    }
    gauge.push_back(best);
  }
  const char* axes[] = {"x", "y", "z"};
  std::vector<std::string> H = {
      "time",         "step",          "dt",           "kinetic_energy", "internal_energy",
      "total_energy", "external_work", "energy_error", "max_pressure"};
  for (const io::SphGauge& g : s.gauges) {
    H.push_back(g.name + "_pressure");
    H.push_back(g.name + "_density");
    H.push_back(g.name + "_von_mises");
    H.push_back(g.name + "_yield_stress");
    H.push_back(g.name + "_plastic_strain");
    for (int d = 0; d < dims; ++d) H.push_back(g.name + "_v" + axes[d]);
    for (int d = 0; d < dims; ++d) H.push_back(g.name + "_u" + axes[d]);
  }
  R.history = io::History(H);
  for (const io::SphGauge& g : s.gauges)
    for (const char* what : {"pressure", "speed"})
      R.gauge_maxima.emplace_back(g.name + "_" + what, 0.0);

  const double e0 = sph::energies(h).total();
  double dt = 0.0;
  // Von Mises stress of the deviator: sqrt(3/2 S:S).
  const auto von_mises = [&](int i) {
    const double* si = &P.S[6 * static_cast<std::size_t>(i)];
    return std::sqrt(1.5 * (si[0] * si[0] + si[1] * si[1] + si[2] * si[2] +
                            2.0 * (si[3] * si[3] + si[4] * si[4] + si[5] * si[5])));
  };
  const auto max_pressure = [&]() { return *std::max_element(P.p.begin(), P.p.end()); };
  const auto record = [&]() {
    const sph::Energies E = sph::energies(h);
    // The balance: total energy against its start plus the work of the loads.
    const double err = std::abs(E.total() - e0 - h.external_work) /
                       std::max({std::abs(e0), std::abs(h.external_work), E.kinetic,
                                 std::abs(E.internal), 1e-300});
    R.energy_error = std::max(R.energy_error, err);
    std::vector<double> row{h.time,
                            static_cast<double>(h.step),
                            dt,
                            E.kinetic,
                            E.internal,
                            E.total(),
                            h.external_work,
                            err,
                            max_pressure()};
    for (int i : gauge) {
      row.push_back(P.p[i]);
      row.push_back(P.rho[i]);
      row.push_back(von_mises(i));
      row.push_back(materials::current_yield(h.materials[P.material[i]].strength, P.p[i],
                                             P.alpha[i], P.damage[i], P.strain_rate[i]));
      row.push_back(P.alpha[i]);
      for (int d = 0; d < dims; ++d) row.push_back(P.v[3 * i + d]);
      for (int d = 0; d < dims; ++d) row.push_back(P.x[3 * i + d] - x0[3 * i + d]);
    }
    R.history.append(std::move(row));
  };
  const auto track = [&]() {
    R.peak_pressure = std::max(R.peak_pressure, max_pressure());
    for (std::size_t k = 0; k < gauge.size(); ++k) {
      const int i = gauge[k];
      const double speed = std::sqrt(P.v[3 * i] * P.v[3 * i] + P.v[3 * i + 1] * P.v[3 * i + 1] +
                                     P.v[3 * i + 2] * P.v[3 * i + 2]);
      R.gauge_maxima[2 * k].second = std::max(R.gauge_maxima[2 * k].second, std::abs(P.p[i]));
      R.gauge_maxima[2 * k + 1].second = std::max(R.gauge_maxima[2 * k + 1].second, speed);
    }
  };
  // The body's particles only (mirror images beyond them are not written).
  io::FieldOutput fields(out, "fields", x0);
  fields.vector("displacement", [&](std::vector<double>& u) {
    u.assign(P.x.begin(), P.x.begin() + 3 * static_cast<std::ptrdiff_t>(n));
    for (std::size_t k = 0; k < u.size(); ++k) u[k] -= x0[k];
  });
  fields.vector("velocity", P.v);
  fields.scalar("density", P.rho);
  fields.scalar("pressure", P.p);
  fields.scalar("specific_energy", P.e);
  fields.scalar("smoothing_length", P.h);
  fields.scalar("von_mises", [&](std::vector<double>& mises) {
    mises.resize(n);
    for (int i = 0; i < n; ++i) mises[i] = von_mises(i);
  });
  fields.scalar("plastic_strain", P.alpha);
  fields.scalar("damage", P.damage);
  fields.scalar("failed", P.failed);
  fields.scalar("material", P.material);
  const auto write_fields = [&]() { fields.write(h.time); };

  track();
  record();
  write_fields();
  double next_history = s.history_interval, next_fields = s.fields_interval;
  double next_progress = 0.1 * s.end_time;
  R.smallest_dt = std::numeric_limits<double>::infinity();
  const auto t_start = Clock::now();
  while (h.time < s.end_time * (1.0 - 1e-12)) {
    int limiting = -1;
    const double stable = sph::stable_step(h, &limiting);
    if (!(stable > 0.0) || !std::isfinite(stable)) {
      R.status = "failed";
      R.stop_reason = detail::concat("no finite CFL step at t = ", h.time, " (step ", h.step,
                                     ", particle ", limiting, ")");
      break;
    }
    dt = std::min(stable, s.end_time - h.time);
    if (h.step == 0) R.first_dt = dt;
    if (stable < R.smallest_dt) {
      R.smallest_dt = stable;
      R.dt_limit = detail::concat(
          "CFL step ", stable, " (Courant ", s.settings.courant, ") set at step ", h.step,
          " by particle ", limiting, " at (", P.x[3 * limiting], ", ", P.x[3 * limiting + 1], ", ",
          P.x[3 * limiting + 2], "), h ", P.h[limiting], ", c ", P.c[limiting]);
    }
    try {
      sph::advance(h, dt);
    } catch (const Error& e) {
      R.status = "failed";
      R.stop_reason = e.what();
      break;
    }
    track();
    if (s.history_interval <= 0.0 || h.time >= next_history * (1 - 1e-12)) {
      record();
      while (s.history_interval > 0.0 && next_history <= h.time * (1 + 1e-12))
        next_history += s.history_interval;
    }
    if (s.fields_interval > 0.0 && h.time >= next_fields * (1 - 1e-12)) {
      write_fields();
      while (next_fields <= h.time * (1 + 1e-12)) next_fields += s.fields_interval;
    }
    if (h.time >= next_progress) {
      log::info("  t = ", h.time, " (", static_cast<int>(std::lround(100 * h.time / s.end_time)),
                "%), step ", h.step, ", dt ", dt, ", max pressure ", max_pressure(), ", ",
                seconds_since(t_start), " s");
      next_progress += 0.1 * s.end_time;
    }
  }
  const double stepping = seconds_since(t_start);
  R.timer.add("stepping", stepping);
  R.steps = h.step;
  R.neighbour_rebuilds = h.rebuilds;
  R.particle_steps_per_second = stepping > 0.0 ? static_cast<double>(n) * h.step / stepping : 0.0;
  if (R.status == "completed") {
    if (R.history.last()[0] < h.time) record();
    write_fields();
  }
  fields.close();
  if (R.status != "completed") log::info("stopped: ", R.stop_reason);
  log::info("done: ", R.steps, " steps, ", R.neighbour_rebuilds, " neighbour-list builds, ",
            R.particle_steps_per_second, " particle steps/s, largest energy error ",
            R.energy_error);
  log::info("smallest step: ", R.dt_limit);
  return R;
}

void write_sph_outputs(const io::ProblemSpec& spec, const SphResult& r, io::OutputDirectory& out) {
  r.history.write(out);
  io::Summary summary({spec.name, spec.description, spec.units, "sph", ""});
  summary.set_status(r.status, r.stop_reason);
  summary.section("counts")
      .set("particles", r.particles)
      .set("steps", r.steps)
      .set("neighbour_list_builds", r.neighbour_rebuilds);
  summary.section("time_step")
      .set("first", r.first_dt)
      .set("smallest", r.smallest_dt)
      .set("limited_by", r.dt_limit);
  io::Json gauges;
  for (const auto& [name, value] : r.gauge_maxima) gauges.set(name, value);
  summary.section("results")
      .set("peak_pressure", r.peak_pressure)
      .set("energy_error_relative", r.energy_error)
      .set("particle_steps_per_second", r.particle_steps_per_second)
      .set("gauge_maxima", gauges);
  summary.write(out, r.timer);
}

} // namespace mf::app
