// The SPH part of a problem file (analysis: sph): numerics, the regions of particles and their
// materials' equations of state and strength, boundary conditions (blasts, transmitting
// boundaries, constant tractions, symmetry planes), gravity, detonation, viscosity, time and
// output. Every key is checked; errors name the key path.
#include "meshfree/core/memory.hpp"
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>
#include <cmath>
#include <variant>

namespace mf::spec {

namespace {

/// The checks of a material the particles use: an equation of state, and for a solid with
/// plasticity its shear modulus.
void take_material(const MaterialSpec& m) {
  if (!m.eos) material_error(m, "eos", "analysis sph needs an equation of state");
  const bool j2 = !m.strength || m.strength->model == StrengthSpec::Model::J2;
  if (m.strength && j2 && !m.plasticity)
    material_error(m, "plasticity", "a J2 strength needs the material's 'plasticity'");
  if (j2 && m.plasticity && !(m.shear_modulus > 0.0))
    material_error(m, "shear_modulus",
                   "analysis sph needs the shear modulus (or E and nu) of a "
                   "solid with plasticity");
}

/// `key`: [min, max] multiples of a particle's initial smoothing length (SmoothingBounds), or
/// `otherwise` when it is not given.
SmoothingBounds read_smoothing_bounds(KeyReader& r, const std::string& key,
                                      const SmoothingBounds& otherwise) {
  if (!r.has(key)) return otherwise;
  const std::vector<double> v = r.numbers(key, 2);
  if (!(v[0] > 0.0 && v[0] <= 1.0 && v[1] >= 1.0 && std::isfinite(v[1])))
    r.error(key, "expected [min, max] multiples of the initial smoothing length with "
                 "0 < min <= 1 <= max, got [" +
                     detail::concat(v[0]) + ", " + detail::concat(v[1]) + "]");
  return {v[0], v[1]};
}

/// `key`: one of the model's axes, x, y or z (dimension `dim`), as its index.
int read_axis(KeyReader& r, const std::string& key, int dim) {
  const std::vector<std::string> axes{"x", "y", "z"};
  const std::string axis =
      r.choice(key, std::vector<std::string>(axes.begin(), axes.begin() + dim), "");
  return static_cast<int>(std::find(axes.begin(), axes.end(), axis) - axes.begin());
}

/// velocity_profile: {along, component, table}, one velocity component along one axis.
SphRegion::VelocityProfile read_velocity_profile(KeyReader& v, int dim) {
  SphRegion::VelocityProfile p;
  p.along = read_axis(v, "along", dim);
  p.component = read_axis(v, "component", dim);
  p.table = read_table(v, "table", 2, false);
  v.finish();
  return p;
}

/// A region of particles from a geometry file (2D): `file` and `scale`, and `group`, one of its
/// groups of surfaces (else the whole body); the lattice is laid over the body's box and kept
/// inside the body.
void read_file_region(KeyReader& b, int dim, const std::string& base_dir, Region& region) {
  if (dim != 2) b.error("file", "a region of particles is read from a file in 2D only so far");
  geometry::OutlineFile file = read_geometry_file(b, base_dir);
  geometry::Domain body = b.has("group") ? file_part(b, file.parts).body : std::move(file.body);
  if (const std::optional<geometry::Annulus> ring = geometry::annulus_of(body)) {
    region.ring = Ring{Point(ring->center.x(), ring->center.y(), 0.0), ring->inner, ring->outer};
    return;
  }
  const BoundingBox bb = body.bounds();
  region.box = Box{Point(bb.lo.x(), bb.lo.y(), 0.0), Point(bb.hi.x(), bb.hi.y(), 0.0)};
  region.part = std::move(body);
}

SphRegion read_region_of_particles(KeyReader& b, int dim, double spacing,
                                   const std::vector<MaterialSpec>& materials,
                                   const SmoothingBounds& bounds, const std::string& base_dir) {
  SphRegion block;
  block.key_path = b.path();
  block.material = find_material(b, "material", materials, b.text("material"));
  const MaterialSpec& mat = materials[block.material];
  if (b.has("box") + b.has("ring") + b.has("file") != 1)
    b.error("box", "give exactly one of 'box', 'ring' or 'file'");
  block.spacing = spacing > 0.0 ? b.positive("spacing", spacing) : b.positive("spacing");
  block.region = read_region(b, dim, kSolids);
  if (b.has("file")) read_file_region(b, dim, base_dir, block.region);
  const Region& g = block.region;
  double particles = 1.0; // an estimate in floating point, so that no count can overflow
  if (g.ring) {
    if (block.spacing > g.ring->outer_radius - g.ring->inner_radius)
      b.error("spacing", "larger than the ring's thickness");
    const double ro = g.ring->outer_radius, ri = g.ring->inner_radius;
    particles = M_PI * (ro * ro - ri * ri) / (block.spacing * block.spacing);
  } else {
    for (int d = 0; d < dim; ++d)
      if (!(g.box->hi[d] > g.box->lo[d])) b.error("box", "the box is empty along an axis");
    for (int d = 0; d < dim; ++d)
      if (block.spacing > g.box->hi[d] - g.box->lo[d])
        b.error("spacing", "larger than the box along an axis");
    for (int d = 0; d < dim; ++d) particles *= (g.box->hi[d] - g.box->lo[d]) / block.spacing + 1.0;
  }
  require_memory(b.path_of("spacing"), "particles in this region", particles,
                 bytes_per::sph_particle(dim));
  const materials::EquationOfState& eos = *mat.eos;
  const auto* explosive = std::get_if<materials::JwlExplosive>(&eos);
  const auto* ideal_gas = std::get_if<materials::IdealGas>(&eos);
  const auto* hjc = std::get_if<materials::Hjc>(&eos);
  const auto* compaction = std::get_if<materials::Compaction>(&eos);
  // The material's density, else the reference density of its equation of state.
  double natural = mat.density;
  if (!(natural > 0.0) && explosive) natural = explosive->jwl.rho0;
  if (!(natural > 0.0) && hjc) natural = hjc->rho0;
  if (!(natural > 0.0) && compaction) natural = compaction->loading.x.front();
  block.density = b.positive("density", natural);
  if (!(block.density > 0.0)) b.error("density", "required value is missing");
  const bool energy_free = compaction || hjc;
  if (energy_free && b.has("energy"))
    b.error("energy", "this equation of state does not depend on the internal energy");
  if (b.has("pressure") == b.has("energy") && !explosive && !energy_free)
    b.error("energy", "give exactly one of 'energy' (J/kg) or 'pressure'");
  block.state_key = b.has("pressure") ? "pressure" : b.has("energy") ? "energy" : "density";
  if (b.has("pressure")) {
    if (!ideal_gas)
      b.error("pressure", "an initial pressure is turned into energy for an ideal gas only; "
                          "give 'energy'");
    block.energy = b.positive("pressure") / ((ideal_gas->gamma - 1.0) * block.density);
  } else {
    block.energy = b.number("energy", explosive ? explosive->jwl.e0 : 0.0);
  }
  if (b.has("velocity")) block.velocity = read_point(b, "velocity", dim);
  b.allow("velocity");
  if (auto v = b.optional_map("velocity_profile"))
    block.velocity_profile = read_velocity_profile(*v, dim);
  block.fixed = b.choice("motion", {"free", "fixed"}, "free") == "fixed";
  block.smoothing_bounds = read_smoothing_bounds(b, "smoothing_bounds", bounds);
  if (block.fixed && b.has("velocity")) b.error("velocity", "a fixed region does not move");
  if (block.fixed && block.velocity_profile)
    b.error("velocity_profile", "a fixed region does not move");
  b.finish();
  return block;
}

/// One entry of `boundary:`: a blast, a transmitting boundary, a constant traction or a symmetry
/// plane.
void read_condition(KeyReader& c, int dim, SphSpec& s) {
  const std::string name = c.text("name");
  check_name(c, "name", name);
  int given = 0;
  for (const char* k : {"blast", "transmitting", "traction", "symmetry"}) given += c.has(k) ? 1 : 0;
  if (given != 1) c.error("name", "give exactly one of blast, transmitting, traction or symmetry");
  if (c.has("symmetry")) {
    KeyReader m = c.map("symmetry");
    SphSymmetry plane;
    plane.name = name;
    plane.axis = read_axis(m, "axis", dim);
    plane.at = m.number("at");
    for (const auto& other : s.symmetry)
      if (other.axis == plane.axis)
        m.error("axis", std::string("another symmetry plane is normal to ") + "xyz"[plane.axis]);
    m.finish();
    s.symmetry.push_back(plane);
  } else {
    const Region region = read_region(c, dim, kSolids);
    if (region.everything()) c.error("box", "a boundary needs the region of its particles");
    if (c.has("blast")) {
      SphBlastLoad load;
      load.key_path = c.path();
      load.name = name;
      load.region = region;
      KeyReader b = c.map("blast");
      load.blast = read_blast(b, dim, true);
      s.loads.push_back(load);
    } else if (c.has("traction")) {
      SphTraction t;
      t.key_path = c.path();
      t.name = name;
      t.region = region;
      t.traction = read_point(c, "traction", dim);
      s.tractions.push_back(t);
    } else {
      SphTransmitting t;
      t.key_path = c.path();
      t.name = name;
      t.region = region;
      KeyReader m = c.map("transmitting");
      t.normal = read_unit_vector(m, "normal", dim);
      m.finish();
      s.transmitting.push_back(t);
    }
  }
  for (const char* k : {"blast", "transmitting", "traction", "symmetry"}) c.allow(k);
  c.finish();
}

/// discretisation: returns the particle spacing (0 when each region gives its own).
double read_discretisation(KeyReader& r, SphSpec& s) {
  double spacing = 0.0;
  if (auto m = r.optional_map("discretisation")) {
    spacing = m->positive("spacing", 0.0);
    s.smoothing = m->positive("smoothing", 1.5);
    s.numerics.kernel =
        m->choice("kernel", {"cubic_spline", "wendland_c2"}, "cubic_spline") == "cubic_spline"
            ? kernels::SphKernel::CubicSpline
            : kernels::SphKernel::WendlandC2;
    s.numerics.gradient_correction = m->choice("gradient_correction", {"off", "on"}, "off") == "on";
    s.numerics.deterministic = m->choice("deterministic", {"true", "false"}, "false") == "true";
    s.smoothing_bounds = read_smoothing_bounds(*m, "smoothing_bounds", s.smoothing_bounds);
    if (s.smoothing < 1.0 || s.smoothing > 3.0)
      m->error("smoothing",
               "expected h / spacing between 1 and 3, got " + std::to_string(s.smoothing));
    m->finish();
  }
  return spacing;
}

/// The regions of particles, and the materials they use (checked) in the order of the list.
void read_regions(KeyReader& r, const std::vector<MaterialSpec>& all, int dim, double spacing,
                  const std::string& base_dir, SphSpec& s) {
  std::vector<KeyReader> regions = r.map_list("regions");
  if (regions.empty()) r.error("regions", "at least one region of particles is required");
  std::vector<char> used(all.size(), 0);
  for (KeyReader& b : regions) used[find_material(b, "material", all, b.text("material"))] = 1;
  for (std::size_t k = 0; k < all.size(); ++k)
    if (used[k]) {
      take_material(all[k]);
      s.materials.push_back(all[k]);
    }
  for (KeyReader& b : regions)
    s.regions.push_back(
        read_region_of_particles(b, dim, spacing, s.materials, s.smoothing_bounds, base_dir));
}

/// detonation: a point, or a plane {at, normal}, and the burn front's width and ignition.
void read_detonation(KeyReader& r, int dim, SphSpec& s) {
  if (auto d = r.optional_map("detonation")) {
    if (d->has("point") == d->has("plane"))
      d->error("point", "give exactly one of 'point' or 'plane: {at, normal}'");
    if (d->has("point")) {
      s.detonation_point = read_point(*d, "point", dim);
    } else {
      KeyReader plane = d->map("plane");
      s.detonation_point = read_point(plane, "at", dim);
      s.detonation_normal = read_unit_vector(plane, "normal", dim);
      plane.finish();
    }
    s.numerics.burn_width = d->positive("burn_width", s.numerics.burn_width);
    s.numerics.ignition_compression =
        d->positive("ignition_compression", s.numerics.ignition_compression);
    d->finish();
  }
}

void read_viscosity(KeyReader& r, sph::Settings& n) {
  if (auto v = r.optional_map("viscosity")) {
    n.alpha = v->number("alpha", 1.0);
    n.beta = v->number("beta", 1.0);
    n.phi = v->positive("phi", 0.1);
    if (n.alpha < 0.0 || n.beta < 0.0)
      v->error("alpha", "the viscosity coefficients must not be negative");
    v->finish();
  }
}

void read_artificial_stress(KeyReader& r, sph::Settings& n) {
  if (auto a = r.optional_map("artificial_stress")) {
    n.artificial_stress = a->positive("epsilon", 0.3);
    n.artificial_stress_exponent = a->integer("exponent", 4, 1, 12);
    a->finish();
  }
}

/// interface: the inter-material penalty force (sph::Settings::Penalty).
void read_interface_penalty(KeyReader& r, sph::Settings& n) {
  if (auto f = r.optional_map("interface")) {
    sph::Settings::Penalty& pen = n.penalty;
    pen.pressure = f->positive("penalty_pressure");
    pen.n1 = f->integer("n1", 12, 1, 32);
    pen.n2 = f->integer("n2", 6, 0, 31);
    pen.distance = f->positive("distance", 1.0);
    if (pen.n2 >= pen.n1) f->error("n2", "must be smaller than n1 for a repulsive force");
    if (pen.distance > 2.0) f->error("distance", "expected at most 2 particle spacings");
    f->finish();
  }
}

void read_output(KeyReader& r, int dim, SphSpec& s) {
  if (auto o = r.optional_map("output")) {
    s.output = read_series_output(*o, dim);
    o->finish();
  }
}

} // namespace

SphSpec parse_sph(KeyReader& r, const ProblemSpec& front, const std::string& base_dir) {
  SphSpec s;
  if (front.model_type == ModelType::PlaneStress)
    r.error("model", "analysis sph takes model.type uniaxial_strain, plane_strain or solid_3d");
  s.dimension = front.dimension;
  s.smoothing_bounds = SmoothingBounds::defaults(s.dimension);
  const int dim = s.dimension;
  const double spacing = read_discretisation(r, s);
  read_regions(r, front.materials, dim, spacing, base_dir, s);
  for (KeyReader& c : r.map_list("boundary")) read_condition(c, dim, s);
  if (r.has("gravity")) s.gravity = read_point(r, "gravity", dim);
  r.allow("gravity");
  read_detonation(r, dim, s);
  read_viscosity(r, s.numerics);
  read_artificial_stress(r, s.numerics);
  read_interface_penalty(r, s.numerics);
  const TimeSpec t = read_time(r, StepControl::Courant);
  s.end_time = t.end;
  s.numerics.courant = t.courant;
  read_output(r, dim, s);
  return s;
}

} // namespace mf::spec
