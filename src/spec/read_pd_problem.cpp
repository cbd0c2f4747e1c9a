// The peridynamics part of a problem file (analysis: peridynamics): the materials the body uses
// and their interfaces, the particles, regions, cracks and notches, time functions, boundary
// conditions, impactors, time and output. Every key is checked; errors name the key path.
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <cmath>

namespace mf::spec {

namespace {

int find_function(KeyReader& r, const std::string& key, const PdSpec& s) {
  if (!r.has(key)) {
    r.allow(key);
    return -1;
  }
  const std::string name = r.text(key);
  for (std::size_t k = 0; k < s.functions.size(); ++k)
    if (s.functions[k].name == name) return static_cast<int>(k);
  r.error(key, "no function is named '" + one_line(name) + "'");
}

PdFunction read_function(KeyReader& f, const std::string& base_dir, const PdSpec& s) {
  PdFunction out;
  out.name = f.text("name");
  check_name(f, "name", out.name);
  for (const auto& other : s.functions)
    if (other.name == out.name) f.error("name", "another function is named '" + out.name + "'");
  const std::string type = f.choice("type", {"constant", "ramp", "sine", "table"}, "");
  loads::TimeFunction& tf = out.f;
  if (type == "constant") {
    tf.kind = loads::TimeFunction::Kind::Constant;
    tf.value = f.number("value");
  } else if (type == "ramp") {
    tf.kind = loads::TimeFunction::Kind::Ramp;
    tf.t0 = f.number("start", 0.0);
    tf.t1 = f.number("end");
    if (!(tf.t1 > tf.t0)) f.error("end", "the ramp must end after it starts");
  } else if (type == "sine") {
    tf.kind = loads::TimeFunction::Kind::Sine;
    tf.amplitude = f.number("amplitude", 1.0);
    tf.omega = f.positive("omega");
    tf.phase = f.number("phase", 0.0);
    tf.duration = f.positive("duration", 0.0);
  } else {
    tf.kind = loads::TimeFunction::Kind::Table;
    out.file = f.text("file");
    const std::string path =
        !out.file.empty() && out.file.front() == '/' ? out.file : base_dir + out.file;
    try {
      tf.samples = loads::read_samples(path);
    } catch (const Error& e) {
      f.error("file", e.what());
    }
    tf.duration = f.positive("duration");
    const double scale = f.number("scale", 1.0);
    for (double& v : tf.samples) v *= scale;
    out.haar_level = f.integer("haar_level", 0, 0, 10);
    // Level j holds block means of 2^j samples, each for 2^j original sample steps (the last
    // block of an odd-length level is padded, so N_j 2^j can exceed N by a few samples).
    const double step0 = tf.duration / static_cast<double>(tf.samples.size());
    tf.samples = loads::haar_approximation(tf.samples, out.haar_level);
    tf.sample_step = step0 * std::pow(2.0, out.haar_level);
  }
  f.finish();
  return out;
}

PdCondition read_condition(KeyReader& c, const PdSpec& s, int dim) {
  PdCondition out;
  out.key_path = c.path();
  out.name = c.text("name");
  check_name(c, "name", out.name);
  for (const auto& other : s.conditions)
    if (other.name == out.name) c.error("name", "another condition is named '" + out.name + "'");
  const Region region = read_region(c, dim, kSolids);
  if (!region.everything()) out.region = region;
  const char* kinds[] = {"displacement", "velocity", "traction", "body_force", "blast"};
  int given = 0;
  for (const char* k : kinds) given += c.has(k) ? 1 : 0;
  if (given != 1)
    c.error("name", "give exactly one of displacement, velocity, traction, body_force or blast");
  if (c.has("displacement") || c.has("velocity")) {
    const bool vel = c.has("velocity");
    out.kind = vel ? PdCondition::Kind::Velocity : PdCondition::Kind::Displacement;
    KeyReader v = c.map(vel ? "velocity" : "displacement");
    const char* axes[] = {"x", "y", "z"};
    for (int d = 0; d < dim; ++d)
      if (v.has(axes[d])) out.fixed[d] = true, out.value(d) = v.number(axes[d]);
    v.finish();
    if (!out.fixed[0] && !out.fixed[1] && !out.fixed[2])
      c.error(vel ? "velocity" : "displacement", "prescribe at least one component");
    if (!out.region) c.error("box", "a prescribed motion needs the region of particles it acts on");
  } else if (c.has("traction")) {
    out.kind = PdCondition::Kind::Traction;
    out.value = read_point(c, "traction", dim);
    out.area = c.positive("area", 0.0);
    if (!out.region) c.error("box", "a traction needs the region of the loaded layer of particles");
  } else if (c.has("blast")) {
    out.kind = PdCondition::Kind::Blast;
    KeyReader b = c.map("blast");
    out.blast = read_blast(b, dim, false);
    if (!out.region)
      c.error("box", "a blast load needs the region of the loaded layer of particles");
  } else {
    out.kind = PdCondition::Kind::BodyForce;
    out.value = read_point(c, "body_force", dim);
  }
  for (const char* k : kinds) c.allow(k);
  out.function = find_function(c, "function", s);
  c.finish();
  return out;
}

/// The checks of a material the body uses: E, density and bond parameters.
void take_material(const MaterialSpec& m, materials::PdDimension dimension) {
  const std::string needs = "analysis peridynamics needs ";
  if (!(m.density > 0.0)) material_error(m, "density", needs + "a density");
  if (!m.bond) material_error(m, "bond", needs + "bond parameters (bond: {law: pmb, ...})");
  if (m.bond->lps) {
    // E and nu (or E and G), or the bulk and shear moduli LAMMPS peri/lps takes.
    const bool from_E = m.E > 0.0 && m.has_nu;
    const bool from_K = m.bulk_modulus > 0.0 && m.shear_modulus > 0.0 && !(m.E > 0.0);
    if (!from_E && !from_K)
      material_error(m, "nu",
                     "law: lps needs the material's E and nu (or E and shear_modulus), "
                     "or bulk_modulus and shear_modulus");
    if (from_E && m.bulk_modulus > 0.0)
      material_error(m, "bulk_modulus", "give E and nu, or bulk_modulus and shear_modulus");
    if (m.bond->yield_stress > 0.0 && dimension != materials::PdDimension::Solid3D)
      material_error(m, "bond.law",
                     "law: eps (Mitchell 2011) is a 3D model; use model.type "
                     "solid_3d");
    return;
  }
  if (!(m.E > 0.0)) material_error(m, "E", needs + "Young's modulus E");
  if (m.bulk_modulus > 0.0 && m.bond->micromodulus > 0.0)
    material_error(m, "bond.micromodulus",
                   "give 'micromodulus' or the material's "
                   "'bulk_modulus', not both");
  if (m.bulk_modulus > 0.0 && dimension != materials::PdDimension::Solid3D)
    material_error(m, "bulk_modulus", "the micromodulus from the bulk modulus is a 3D formula");
}

materials::PdDimension read_pd_dimension(KeyReader& r, const ProblemSpec& front) {
  if (front.model_type == ModelType::UniaxialStrain)
    r.error("model", "analysis peridynamics takes model.type plane_stress, plane_strain or "
                     "solid_3d");
  return front.model_type == ModelType::Solid3D       ? materials::PdDimension::Solid3D
         : front.model_type == ModelType::PlaneStress ? materials::PdDimension::PlaneStress
                                                      : materials::PdDimension::PlaneStrain;
}

/// The body's own material: a `material:` reference, or the single entry of the file.
void read_body_material(KeyReader& r, const std::vector<MaterialSpec>& all,
                        const std::vector<PartMaterial>& parts, PdSpec& s) {
  if (r.has("material")) {
    s.body_material = find_material(r, "material", all, r.text("material"));
  } else if (!parts.empty()) {
    s.body_material = parts.front().material; // every particle lies in a part
  } else if (all.size() != 1) {
    r.error("material", "name the material of the body (the file lists " +
                            std::to_string(all.size()) + " materials)");
  }
  r.allow("material");
}

PdInterface read_interface(KeyReader& i, const std::vector<MaterialSpec>& all,
                           std::vector<char>& used) {
  PdInterface f;
  const YAML::Node names = i.raw("materials");
  if (!names.IsSequence() || names.size() != 2)
    i.error("materials", "expected the two material names [a, b]");
  f.a = names[0].as<std::string>();
  f.b = names[1].as<std::string>();
  used[find_material(i, "materials", all, f.a)] = 1;
  used[find_material(i, "materials", all, f.b)] = 1;
  f.base = i.text("base", f.a);
  used[find_material(i, "base", all, f.base)] = 1;
  f.yield_stretch_factor = i.positive("yield_stretch_factor", 1.0);
  f.critical_stretch_factor = i.positive("critical_stretch_factor", 1.0);
  i.finish();
  return f;
}

void read_discretisation(KeyReader& r, PdSpec& s) {
  KeyReader d = r.map("discretisation");
  s.spacing = d.positive("spacing");
  s.horizon_factor = d.positive("horizon", 3.0);
  if (s.horizon_factor < 1.0 || s.horizon_factor > 10.0)
    d.error("horizon",
            "expected delta / spacing between 1 and 10, got " + detail::concat(s.horizon_factor));
  s.volume_correction = d.choice("volume_correction", {"exact", "linear", "none"}, "exact");
  s.surface_correction =
      d.choice("surface_correction", {"none", "energy", "position_aware"}, "none");
  s.short_range_contact = d.choice("short_range_contact", {"false", "true"}, "false") == "true";
  s.deterministic = d.choice("deterministic", {"true", "false"}, "false") == "true";
  d.finish();
}

PdRegion read_pd_region(KeyReader& g, int dim, const std::vector<MaterialSpec>& all,
                        std::vector<char>& used) {
  PdRegion reg;
  reg.region = read_region(g, dim, kSolids);
  if (g.has("material")) {
    reg.material = find_material(g, "material", all, g.text("material"));
    used[reg.material] = 1;
  }
  g.allow("material");
  if (g.has("velocity")) reg.velocity = read_point(g, "velocity", dim);
  g.allow("velocity");
  if (reg.material < 0 && !reg.velocity)
    g.error("material", "a region sets a 'material', a 'velocity' or both");
  g.finish();
  return reg;
}

/// Keeps the used materials of `all` (checked) in s.materials and renumbers the body's and the
/// regions' material indices into that list.
void keep_used_materials(const std::vector<MaterialSpec>& all, const std::vector<char>& used,
                         PdSpec& s) {
  std::vector<int> index(all.size(), -1);
  for (std::size_t k = 0; k < all.size(); ++k)
    if (used[k]) {
      take_material(all[k], s.dimension);
      index[k] = static_cast<int>(s.materials.size());
      s.materials.push_back(all[k]);
    }
  s.body_material = index[s.body_material];
  for (PdRegion& g : s.regions)
    if (g.material >= 0) g.material = index[g.material];
}

/// The body's materials are all bond-based or all state-based with one influence function; a
/// state-based body takes no energy-method surface correction (its weighted volumes already
/// make the dilatation exact at the surface).
void check_one_family(const PdSpec& s) {
  const MaterialSpec& first = s.materials[s.body_material];
  for (const MaterialSpec& m : s.materials) {
    if (m.bond->lps != first.bond->lps)
      material_error(m, "bond.law",
                     "a body's materials are all state-based (lps) or all "
                     "bond-based; '" +
                         first.name + "' is " + (first.bond->lps ? "lps" : "bond-based"));
    if (m.bond->lps && m.bond->influence != first.bond->influence)
      material_error(m, "bond.influence", "a body's lps materials share one influence function");
  }
  if (s.surface_correction == "energy" && s.state_based())
    fail(s.key_prefix, "discretisation.surface_correction: energy corrects bond-based bodies; an "
                       "lps body takes position_aware");
  if (s.surface_correction == "position_aware" && !s.state_based())
    fail(s.key_prefix, "discretisation.surface_correction: position_aware corrects lps bodies; a "
                       "bond-based body takes energy");
  for (const MaterialSpec& m : s.materials)
    if (s.surface_correction == "position_aware" && m.bond && m.bond->lps &&
        m.bond->yield_stress > 0.0)
      fail(s.key_prefix,
           "discretisation.surface_correction: position_aware is elastic; '" + m.name +
               "' is eps (its plastic return is Mitchell's, on the LPS's own influence)");
}

PdCrack read_crack(KeyReader& c, int dim) {
  PdCrack k;
  k.a = read_point(c, "from", dim);
  k.b = read_point(c, "to", dim);
  if (dim == 3) k.c = read_point(c, "to2", dim);
  c.allow("to2");
  c.finish();
  return k;
}

/// cracks: [{curve: name}]: a group of the geometry file's curves (2D) as pre-cracks, each
/// segment one crack and each arc its chords, each turning at most 5 degrees (the reader's bound
/// for curves it draws as chords).
std::vector<PdCrack> read_curve_cracks(KeyReader& c, int dim, const ProblemSpec& front) {
  const std::string name = c.text("curve");
  if (dim != 2 || front.file_curves.empty())
    c.error("curve", "names a group of curves of a plane geometry file (geometry.file), and the "
                     "body has none");
  const geometry::FileCurve* curve = nullptr;
  std::string known;
  for (const geometry::FileCurve& f : front.file_curves) {
    if (f.name == name) curve = &f;
    known += (known.empty() ? "" : ", ") + f.name;
  }
  if (!curve)
    c.error("curve", "the geometry file has no group of curves named '" + one_line(name) +
                         "' (its groups of curves: " + known + ")");
  c.finish();
  std::vector<PdCrack> out;
  for (const geometry::Curve& piece : curve->pieces) {
    const double turn = std::abs(piece.theta1 - piece.theta0);
    const int chords = piece.kind == geometry::Curve::Kind::Arc
                           ? std::max(1, static_cast<int>(std::ceil(turn / (M_PI / 36.0) - 1e-9)))
                           : 1;
    for (int k = 0; k < chords; ++k) {
      const Vec2 a = piece.point(static_cast<double>(k) / chords);
      const Vec2 b = piece.point(static_cast<double>(k + 1) / chords);
      PdCrack crack;
      crack.a = Point(a.x(), a.y(), 0.0);
      crack.b = Point(b.x(), b.y(), 0.0);
      out.push_back(crack);
    }
  }
  return out;
}

/// An impactor's shape: a sphere of a radius, or a flat box of a size.
void read_impactor_shape(KeyReader& k, int dim, PdImpactor& imp) {
  imp.sphere = k.choice("shape", {"sphere", "flat"}, "") == "sphere";
  if (imp.sphere) {
    imp.radius = k.positive("radius");
  } else {
    imp.half_size = 0.5 * read_point(k, "size", dim);
    if (dim == 2) imp.half_size.z() = 1e300;
    if (imp.half_size.minCoeff() <= 0.0) k.error("size", "expected positive extents");
  }
  k.allow(imp.sphere ? "size" : "radius");
  if (k.has(imp.sphere ? "size" : "radius"))
    k.error(imp.sphere ? "size" : "radius", "does not belong to this shape");
}

/// An impactor's motion: free (mass and velocity), fixed (a support) or prescribed (velocity).
void read_impactor_motion(KeyReader& k, int dim, PdImpactor& imp) {
  const std::string motion = k.choice("motion", {"free", "fixed", "prescribed"}, "free");
  imp.fixed = motion == "fixed";
  imp.prescribed = motion == "prescribed";
  if (imp.fixed) {
    if (k.has("mass") || k.has("velocity"))
      k.error("motion", "a fixed impactor (a support) has no mass or velocity");
    k.allow("mass");
    k.allow("velocity");
  } else if (imp.prescribed) {
    if (k.has("mass")) k.error("mass", "a prescribed motion does not depend on a mass");
    k.allow("mass");
    imp.velocity = read_point(k, "velocity", dim);
  } else {
    imp.mass = k.positive("mass");
    imp.velocity = read_point(k, "velocity", dim);
  }
}

void read_impactor_contact(KeyReader& k, PdImpactor& imp) {
  if (auto c = k.optional_map("contact")) {
    imp.penalty = c->choice("type", {"kinematic", "penalty"}, "kinematic") == "penalty";
    if (c->has("stiffness") && !imp.penalty)
      c->error("stiffness", "only a penalty contact has a stiffness");
    if (imp.penalty) imp.stiffness = c->positive("stiffness", 0.0);
    c->allow("stiffness");
    c->finish();
  }
}

PdImpactor read_impactor(KeyReader& k, int dim) {
  PdImpactor imp;
  imp.name = k.text("name");
  check_name(k, "name", imp.name);
  read_impactor_shape(k, dim, imp);
  read_impactor_motion(k, dim, imp);
  read_impactor_contact(k, imp);
  imp.position = read_point(k, "position", dim);
  if (imp.velocity.norm() == 0.0 && !imp.sphere)
    k.error("velocity", "a flat impactor needs a velocity: its direction is the impact direction");
  k.finish();
  return imp;
}

void read_relaxation(KeyReader& r, PdSpec& s) {
  if (auto x = r.optional_map("relaxation")) {
    PdRelaxation relax;
    relax.tolerance = x->positive("tolerance", relax.tolerance);
    if (relax.tolerance >= 1.0) x->error("tolerance", "expected a value below 1");
    relax.max_iterations = x->integer("max_iterations", relax.max_iterations, 1, 100000000);
    x->finish();
    s.relaxation = relax;
  }
}

void read_time_control(KeyReader& r, PdSpec& s) {
  const TimeSpec t = read_time(r, StepControl::Safety);
  s.end_time = t.end;
  s.dt = t.dt;
  s.safety = t.safety;
}

/// output.crack: the crack-tip tracking along a direction from an origin.
void read_crack_output(KeyReader& o, int dim, PdSpec& s) {
  if (auto c = o.optional_map("crack")) {
    s.crack.enabled = true;
    s.crack.threshold = c->positive("damage_threshold", 0.38);
    if (s.crack.threshold >= 1.0) c->error("damage_threshold", "expected a value in (0, 1)");
    s.crack.origin = read_point(*c, "origin", dim);
    s.crack.direction = read_point(*c, "direction", dim);
    if (s.crack.direction.norm() == 0.0) c->error("direction", "expected a nonzero direction");
    s.crack.direction.normalize();
    c->finish();
  }
}

void read_output(KeyReader& r, int dim, PdSpec& s) {
  if (auto o = r.optional_map("output")) {
    s.output = read_series_output(*o, dim);
    read_crack_output(*o, dim, s);
    o->finish();
  }
}

} // namespace

PdSpec parse_pd(KeyReader& r, const ProblemSpec& front, const std::string& base_dir) {
  PdSpec s;
  s.dimension = read_pd_dimension(r, front);
  s.thickness = front.thickness;
  const int dim = front.dimension;
  const std::vector<MaterialSpec>& all = front.materials;
  // The materials the body uses: its own (a `material:` reference or the single entry), those
  // of its regions and those of the interfaces; indices below are into `all` until the end.
  std::vector<char> used(all.size(), 0);
  const std::vector<PartMaterial> parts = read_part_materials(r, front);
  read_body_material(r, all, parts, s);
  used[s.body_material] = 1;
  // Each part of a geometry file is a region of its material, before `regions`, which win.
  for (const PartMaterial& part : parts) {
    PdRegion reg;
    reg.region.part = part.part->body;
    reg.material = part.material;
    used[reg.material] = 1;
    s.regions.push_back(std::move(reg));
  }
  for (KeyReader& i : r.map_list("interfaces"))
    s.interfaces.push_back(read_interface(i, all, used));
  read_discretisation(r, s);
  for (KeyReader& g : r.map_list("regions")) s.regions.push_back(read_pd_region(g, dim, all, used));
  keep_used_materials(all, used, s);
  check_one_family(s);
  for (KeyReader& g : r.map_list("notches")) {
    s.removed.push_back(read_region(g, dim, kSolids));
    if (s.removed.back().everything()) g.error("box", "a notch needs the region it removes");
    g.finish();
  }
  for (KeyReader& c : r.map_list("cracks"))
    if (c.has("curve")) {
      const std::vector<PdCrack> pieces = read_curve_cracks(c, dim, front);
      s.cracks.insert(s.cracks.end(), pieces.begin(), pieces.end());
    } else {
      s.cracks.push_back(read_crack(c, dim));
    }
  for (KeyReader& f : r.map_list("functions")) s.functions.push_back(read_function(f, base_dir, s));
  for (KeyReader& c : r.map_list("boundary")) s.conditions.push_back(read_condition(c, s, dim));
  for (KeyReader& k : r.map_list("impactors")) s.impactors.push_back(read_impactor(k, dim));
  read_relaxation(r, s);
  read_time_control(r, s);
  read_output(r, dim, s);
  return s;
}

} // namespace mf::spec
