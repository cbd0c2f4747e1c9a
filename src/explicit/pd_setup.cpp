#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/distribution/local_part.hpp"
#include "meshfree/explicit/surface_blast.hpp"
#include "meshfree/geometry/lattice.hpp"
#include "meshfree/pd/particle_order.hpp"
#include "meshfree/pd/state_based.hpp"
#include "meshfree/pd/state_surface.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace mf::explicit_dynamics {

namespace {

using spec::Vec3d;

/// Cell-centred lattice of spacing dx over the body: a 3D box, or the 2D domain's bounding box
/// with the points the domain contains; notches left out, regions with their own material.
particles::ParticleSet lattice(const spec::ProblemSpec& spec) {
  const spec::PdSpec& s = spec.pd();
  const double dx = s.spacing;
  const bool solid = s.dimension == materials::PdDimension::Solid3D;
  Vec3d lo, hi;
  if (solid) {
    lo = spec.box->lo;
    hi = spec.box->hi;
  } else {
    const BoundingBox b = spec.domain.bounds();
    lo = Vec3d(b.lo.x(), b.lo.y(), 0.0);
    hi = Vec3d(b.hi.x(), b.hi.y(), 0.0);
  }
  const geometry::Lattice grid = geometry::Lattice::of_spacing(lo, hi, dx, solid ? 3 : 2);
  // Bytes per particle: its arrays and its (4/3) pi m^3 or pi m^2 bond partners for a horizon of
  // m spacings.
  const double m = s.horizon_factor;
  const double partners = solid ? 4.0 / 3.0 * M_PI * m * m * m : M_PI * m * m;
  require_memory("discretisation.spacing", "particles in the body", grid.cells_total(),
                 bytes_per::pd_particle + bytes_per::pd_partner * partners);
  const double volume = solid ? dx * dx * dx : dx * dx * s.thickness;
  particles::ParticleSet p;
  std::vector<long> in_region(s.regions.size(), 0);
  grid.for_each([&](const Vec3d& x) {
    if (!solid && !spec.domain.contains(Vec2(x.x(), x.y()))) return;
    for (const spec::Region& b : s.removed)
      if (b.contains(x, 1e-9 * dx)) return;
    int mat = s.body_material, region = 0;
    for (std::size_t k = 0; k < s.regions.size(); ++k)
      if (s.regions[k].region.contains(x, 1e-9 * dx)) {
        ++in_region[k];
        region = static_cast<int>(k) + 1;
        if (s.regions[k].material >= 0) mat = s.regions[k].material;
      }
    p.add(x, volume, s.materials[mat].density, mat, region);
  });
  MF_REQUIRE(p.size() > 0, "discretisation.spacing: no particle lies in the body");
  for (std::size_t k = 0; k < in_region.size(); ++k)
    MF_REQUIRE(in_region[k] > 0, "regions[", k, "]: holds no particle of the body");
  return p;
}

/// The LPS constants of a material in the body's kinematic setting: from E and nu, or from the
/// bulk and shear moduli.
materials::LpsLaw lps_of(const spec::PdSpec& s, const spec::MaterialSpec& mat) {
  const double K = mat.bulk_modulus > 0.0 ? mat.bulk_modulus : mat.E / (3.0 * (1.0 - 2.0 * mat.nu));
  materials::LpsLaw law = materials::lps_law(s.dimension, K, mat.shear_modulus);
  law.yield_stress = mat.bond->yield_stress;
  return law;
}

/// The bonds of an LPS material: the micromodulus of its short-range contact and impactors, the
/// critical stretch (given, or from G0 by the state-based energy balance) and the LAMMPS alpha.
materials::BondLaw state_law(const spec::PdSpec& s, const spec::MaterialSpec& mat, double delta) {
  const spec::BondSpec& m = *mat.bond;
  const materials::LpsLaw lps = lps_of(s, mat);
  materials::BondLaw law;
  law.c = materials::lps_contact_micromodulus(s.dimension, lps, delta, s.thickness);
  law.critical_stretch =
      m.critical_stretch > 0.0 ? m.critical_stretch
      : m.fracture_energy > 0.0
          ? materials::lps_critical_stretch(s.dimension, lps, m.fracture_energy, delta)
          : 0.0;
  law.alpha = m.alpha;
  return law;
}

/// The bond law of one material: micromodulus (from E, the bulk modulus or given), critical
/// stretch (from G0, given, or none), micro-plastic yield stretch and the LAMMPS alpha.
materials::BondLaw material_law(const spec::PdSpec& s, const spec::MaterialSpec& mat,
                                double delta) {
  const spec::BondSpec& m = *mat.bond;
  if (m.lps) return state_law(s, mat, delta);
  materials::BondLaw law;
  law.c = m.micromodulus > 0.0 ? m.micromodulus
          : mat.bulk_modulus > 0.0
              ? materials::pd_micromodulus_from_bulk(mat.bulk_modulus, delta)
              : materials::pd_micromodulus(s.dimension, mat.E, delta, s.thickness);
  if (m.critical_stretch > 0.0) {
    law.critical_stretch = m.critical_stretch;
  } else if (m.fracture_energy > 0.0) {
    law.critical_stretch =
        mat.bulk_modulus > 0.0 || m.micromodulus > 0.0
            ? materials::pd_critical_stretch_from_c(law.c, m.fracture_energy, delta)
            : materials::pd_critical_stretch(s.dimension, mat.E, m.fracture_energy, delta);
  }
  law.yield_stretch = m.yield_stretch;
  law.alpha = m.alpha;
  return law;
}

/// Laws of every material pair: a material's own law, an interface's base law scaled by its
/// factors, or (pairs with no interface) the law of the pair's softer material.
pd::LawTable law_table(const spec::PdSpec& s, double delta) {
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
  for (const spec::PdInterface& f : s.interfaces) {
    materials::BondLaw law = t.laws[index(f.base)];
    law.yield_stretch *= f.yield_stretch_factor;
    law.critical_stretch *= f.critical_stretch_factor;
    t.laws.push_back(law);
    const int a = index(f.a), b = index(f.b), k = static_cast<int>(t.laws.size()) - 1;
    t.law_of[a * n + b] = t.law_of[b * n + a] = k;
  }
  return t;
}

std::vector<int> particles_in(const particles::ParticleSet& p,
                              const std::optional<spec::Region>& region, double tol) {
  std::vector<int> out;
  for (int i = 0; i < p.size(); ++i)
    if (!region || region->contains(p.reference(i), tol)) out.push_back(i);
  return out;
}

/// Traction t on a layer of particles as a body force: b = t A / (volume of the layer). A is
/// given, or is the layer's volume over its thickness normal to the loaded face (the thinnest
/// extent of the layer, one spacing per particle row), so that b = t / thickness.
Vec3d traction_density(const spec::PdCondition& c, const particles::ParticleSet& p,
                       const std::vector<int>& group, double dx, int dims) {
  double volume = 0.0;
  Vec3d lo = p.reference(group.front()), hi = lo;
  for (int i : group) {
    volume += p.volume[i];
    lo = lo.cwiseMin(p.reference(i));
    hi = hi.cwiseMax(p.reference(i));
  }
  if (c.area > 0.0) return c.value * c.area / volume;
  double thickness = std::numeric_limits<double>::infinity();
  for (int d = 0; d < dims; ++d) thickness = std::min(thickness, hi(d) - lo(d) + dx);
  return c.value / thickness;
}

/// Keeps this rank's block of particles and the ghosts within `reach` of it
/// (distribution::local_part), and the owned members of every constraint and load with their own
/// per-particle values; the halo goes to the model.
void keep_rank_part(PdSetup& out, const distribution::Ranks& ranks, double reach) {
  pd::Model& m = out.model;
  distribution::LocalPart part = distribution::local_part(m.particles, ranks, reach * (1.0 + 1e-9));
  for (pd::Constraint& k : out.loading.constraints)
    distribution::keep_owned(k.particles, k.held, part);
  for (pd::BodyLoad& load : out.loading.loads) {
    std::vector<int> group = load.particles; // filtered once per per-particle array
    distribution::keep_owned(load.particles, load.pulses, part);
    distribution::keep_owned(group, load.densities, part);
  }
  out.first_id = part.first;
  m.particles = std::move(part.particles);
  m.halo = std::move(part.halo);
}

/// The model's parameters from the spec, before it has particles.
pd::Model model_of(const spec::PdSpec& s) {
  pd::Model m;
  m.dimension = s.dimension;
  m.thickness = s.thickness;
  m.spacing = s.spacing;
  m.horizon = s.horizon_factor * s.spacing;
  m.deterministic = s.deterministic;
  for (const auto& mat : s.materials) {
    m.material_names.push_back(mat.name);
    if (mat.bond->lps) m.lps.push_back(lps_of(s, mat)), m.influence = mat.bond->influence;
  }
  return m;
}

pd::Constraint constraint_of(const spec::PdCondition& c, const std::vector<int>& group) {
  pd::Constraint k;
  k.name = c.name;
  k.particles = group;
  k.velocity = c.kind == spec::PdCondition::Kind::Velocity;
  for (int d = 0; d < 3; ++d) k.fixed[d] = c.fixed[d], k.value[d] = c.value(d);
  k.function = c.function;
  return k;
}

/// A body force, a traction as a body force on its layer, or a blast.
pd::BodyLoad load_of(const spec::PdCondition& c, const particles::ParticleSet& p,
                     const std::vector<int>& group, double spacing, int dims) {
  pd::BodyLoad load;
  load.name = c.name;
  load.particles = group;
  load.density = c.kind == spec::PdCondition::Kind::Traction
                     ? traction_density(c, p, group, spacing, dims)
                     : c.value;
  load.function = c.function;
  if (c.kind == spec::PdCondition::Kind::Blast) {
    // Each particle of the layer gets the Friedlander history of its distance and angle of
    // incidence; the force per volume of a unit pressure is -n / (layer thickness). In a
    // plane model the charge lies in the plane and distances are measured in it.
    spec::PdCondition unit = c;
    unit.value = -c.blast.normal;
    unit.area = 0.0;
    load.density = traction_density(unit, p, group, spacing, dims);
    const Charge charge{c.blast.tnt_mass, c.blast.surface_burst, c.blast.clamp_below_range,
                        c.blast.charge, c.blast.normal};
    load.pulses = surface_pulses(charge, p.X, group, c.key_path);
  }
  return load;
}

/// The spec's functions, constraints, loads and initial velocities on the whole body (a
/// traction's layer and a blast's pulses are properties of the whole layer).
void load_body(PdSetup& out, const spec::PdSpec& s) {
  particles::ParticleSet& p = out.model.particles;
  const double tol = 1e-6 * s.spacing;
  for (const auto& f : s.functions) out.loading.functions.push_back(f.f);
  for (const spec::PdCondition& c : s.conditions) {
    const std::vector<int> group = particles_in(p, c.region, tol);
    MF_REQUIRE(!group.empty(), c.key_path, ".box: selects no particle");
    if (c.kind == spec::PdCondition::Kind::Displacement ||
        c.kind == spec::PdCondition::Kind::Velocity)
      out.loading.constraints.push_back(constraint_of(c, group));
    else
      out.loading.loads.push_back(load_of(c, p, group, s.spacing, out.model.plane() ? 2 : 3));
  }
  for (const spec::PdRegion& r : s.regions)
    if (r.velocity)
      for (int i : particles_in(p, r.region, tol))
        for (int d = 0; d < 3; ++d) p.v[3 * i + d] = (*r.velocity)(d);
}

pd::VolumeCorrection volume_correction(const spec::PdSpec& s) {
  return s.volume_correction == "exact"    ? pd::VolumeCorrection::Exact
         : s.volume_correction == "linear" ? pd::VolumeCorrection::Linear
                                           : pd::VolumeCorrection::None;
}

/// The bonds with their laws and surface correction, and the bond state with the pre-cracks.
void bond_body(PdSetup& out, const spec::PdSpec& s, pd::VolumeCorrection correction) {
  pd::Model& m = out.model;
  pd::build_bonds(m, law_table(s, m.horizon), correction);
  if (s.surface_correction == "energy") pd::apply_surface_correction(m);
  std::vector<pd::PreCrack> cracks;
  for (const auto& c : s.cracks) cracks.push_back({c.a, c.b, c.c});
  out.state = pd::initial_state(m, cracks);
  if (m.state_based()) pd::set_weighted_volumes(m, out.state);
  if (s.surface_correction == "position_aware") {
    const long left = pd::apply_position_aware_influence(m, out.state);
    if (left > 0)
      log::warn("discretisation.surface_correction: position_aware: ", left,
                " particles have too few or collinear bonds to fix their influence; they keep "
                "the LPS's");
  }
}

std::vector<pd::Impactor> impactors_of(const spec::PdSpec& s) {
  std::vector<pd::Impactor> out;
  for (const spec::PdImpactor& k : s.impactors) {
    pd::Impactor imp;
    imp.name = k.name;
    imp.shape = k.sphere ? pd::Impactor::Shape::Sphere : pd::Impactor::Shape::Flat;
    imp.radius = k.radius;
    imp.half_size = k.half_size;
    imp.mass = k.mass;
    imp.fixed = k.fixed;
    imp.prescribed = k.prescribed;
    imp.law = k.penalty ? pd::Impactor::Law::Penalty : pd::Impactor::Law::Kinematic;
    imp.stiffness = k.stiffness;
    imp.position = k.position;
    imp.velocity = k.velocity;
    if (!k.sphere) imp.direction = k.velocity.normalized();
    out.push_back(imp);
  }
  return out;
}

/// The stable time step over every rank, and where it is set: the Silling-Askari bound of a
/// bond-based body (a particle sets it), the limit 2 / omega_max of a state-based one.
struct StableStep {
  double local = 0.0; // of this rank's particles
  double stable = 0.0;
  int limiting = -1; // this rank's particle that sets `local`; -1 for the whole body's limit
};

/// The time step: the stable step times the safety factor, one step per load sample when a
/// table is finer, or the step asked for (never above the bound).
void set_time_step(PdSetup& out, const spec::PdSpec& s, const distribution::Ranks& ranks,
                   const StableStep& bound) {
  const double stable = bound.stable;
  out.dt = s.safety * stable;
  const char* source =
      bound.limiting < 0 ? " (2 / omega_max of the linearised body)" : " (Silling & Askari 2005)";
  if (bound.limiting < 0) {
    out.dt_limit = detail::concat("stable step ", stable, source, " times safety ", s.safety);
  } else {
    Vec3d where(0.0, 0.0, 0.0);
    const int holder = ranks.rank_of_min(bound.local);
    if (ranks.rank == holder) where = out.model.particles.reference(bound.limiting);
    ranks.broadcast(where.data(), 3, holder);
    out.dt_limit = detail::concat("stable step ", stable, source, " times safety ", s.safety,
                                  ", set by the particle at (", where.x(), ", ", where.y(), ", ",
                                  where.z(), ")");
  }
  for (std::size_t k = 0; k < s.functions.size(); ++k) {
    const auto& f = s.functions[k];
    if (f.f.kind == loads::TimeFunction::Kind::Table && f.f.sample_step < out.dt) {
      out.dt = f.f.sample_step;
      out.dt_limit = "one step per sample of the load table '" + f.name + "' (" +
                     detail::concat(f.f.sample_step) + ")";
      out.dt_key = detail::concat("functions[", k, "].duration");
    }
  }
  if (s.dt > 0.0) {
    MF_REQUIRE(s.dt <= stable, "time.dt: ", s.dt, " exceeds the stable time step ", stable, source,
               "; velocity Verlet would diverge");
    if (s.dt < out.dt) {
      out.dt = s.dt;
      out.dt_limit = "time.dt";
      out.dt_key = "time.dt";
    }
  }
}

/// The impactors, the contact of particles and the time step of a bonded body.
void set_contact_and_step(PdSetup& out, const spec::PdSpec& s, const distribution::Ranks& ranks) {
  pd::Model& m = out.model;
  out.impactors = impactors_of(s);
  StableStep bound;
  bound.local =
      m.state_based() ? pd::state_stable_time_step(m) : pd::stable_time_step(m, &bound.limiting);
  bound.stable = ranks.min(bound.local);
  MF_REQUIRE(std::isfinite(bound.stable), "peridynamics: no particle has a bond; is the horizon "
                                          "(discretisation.horizon) smaller than the spacing?");
  // A derived penalty stiffness takes the density of the particle that limits the step, or
  // (a state-based body, limited as a whole) the densest of the body's.
  double density = 0.0;
  for (int i : m.particles.owned()) density = std::max(density, m.particles.density[i]);
  density = ranks.max(density);
  if (bound.limiting >= 0) density = m.particles.density[bound.limiting];
  for (pd::Impactor& imp : out.impactors)
    if (imp.law == pd::Impactor::Law::Penalty && imp.stiffness == 0.0)
      imp.stiffness = pd::derived_penalty_stiffness(density, bound.stable, s.spacing);
  // A fragment may fly beyond the ghosts, which are fixed at the start: one rank sees it all.
  MF_REQUIRE(!s.short_range_contact || ranks.serial(),
             "discretisation.short_range_contact: runs on one MPI rank (", ranks.size, " given)");
  if (s.short_range_contact) out.short_range.emplace(m);
  set_time_step(out, s, ranks, bound);
}

} // namespace

PdSetup build_pd_setup(const spec::ProblemSpec& spec, PhaseTimer& timer,
                       const distribution::Ranks& ranks) {
  const spec::PdSpec& s = spec.pd();
  PdSetup out;
  pd::Model& m = out.model;
  m = model_of(s);
  {
    PhaseTimer::Scope scope(timer, "particles");
    m.particles = lattice(spec);
    // Neighbours close in space close in memory; everything below is built in this order.
    pd::order_along_curve(m.particles, s.spacing);
  }
  // Loads, constraints and initial velocities are set on the whole body, then each rank keeps
  // its part.
  out.particles_total = m.particles.size();
  load_body(out, s);
  const pd::VolumeCorrection correction = volume_correction(s);
  if (!ranks.serial()) {
    PhaseTimer::Scope scope(timer, "decomposition");
    keep_rank_part(out, ranks, pd::bond_reach(m, correction));
  }
  {
    PhaseTimer::Scope scope(timer, "bonds");
    bond_body(out, s, correction);
  }
  set_contact_and_step(out, s, ranks);
  return out;
}

void log_pd_setup(const spec::ProblemSpec& spec, const PdSetup& setup) {
  const pd::Model& m = setup.model;
  log::info("peridynamics: ", setup.particles_total, " particles, ", m.bonds.pairs(),
            " bonds, horizon ", m.horizon, " (", spec.pd().horizon_factor, " spacings), ",
            m.laws.size(), " bond law(s)");
  const char* influence[] = {"1 / |xi|", "1", "exp(-|xi|^2 / delta^2)"};
  for (std::size_t k = 0; k < m.lps.size(); ++k)
    log::info("  material '", m.material_names[k], "': state-based ",
              m.lps[k].plastic() ? "EPS" : "LPS", ", kappa ", m.lps[k].kappa, ", mu ", m.lps[k].mu,
              m.lps[k].plastic() ? detail::concat(", yield stress ", m.lps[k].yield_stress) : "",
              ", influence ", influence[static_cast<int>(m.influence)]);
  for (std::size_t k = 0; k < m.laws.size(); ++k)
    log::info("  law ", k, m.state_based() ? ": contact c " : ": c ", m.laws[k].c,
              ", critical stretch ", m.laws[k].critical_stretch,
              m.laws[k].plastic() ? detail::concat(", yield stretch ", m.laws[k].yield_stretch)
                                  : "");
  log::info("time step ", setup.dt, ": ", setup.dt_limit);
  for (const pd::Impactor& imp : setup.impactors)
    if (imp.law == pd::Impactor::Law::Penalty)
      log::info("impactor '", imp.name, "': penalty contact (LAMMPS fix indent), stiffness ",
                imp.stiffness);
  if (setup.short_range) log::info("short-range contact of particles (LAMMPS peri/pmb): on");
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
}

} // namespace mf::explicit_dynamics
