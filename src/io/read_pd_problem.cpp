// The peridynamics part of a problem file (analysis: peridynamics): model, materials and their
// interfaces, the body (a 2D geometry or a 3D box) and its particles, cracks and notches, time
// functions, boundary conditions, impactors, time and output. Every key is checked; errors name
// the key path.
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/pd_read.hpp"
#include <cmath>

namespace mf::io {

namespace {

/// A point or vector with `dim` components (the third is 0 in a plane).
Vec3d read_point(KeyReader& r, const std::string& key, int dim) {
  const std::vector<double> v = r.numbers(key, dim);
  return {v[0], v[1], dim == 3 ? v[2] : 0.0};
}

/// [[x0, y0(, z0)], [x1, y1(, z1)]]; in a plane the box is unbounded in z.
Box3 read_box3(KeyReader& r, const std::string& key, int dim) {
  const auto corners = r.number_lists(key, dim);
  if (corners.size() != 2) r.error(key, "expected two corners [[x0, ...], [x1, ...]]");
  Box3 b;
  for (int d = 0; d < 3; ++d) {
    const double a = d < dim ? corners[0][d] : -1e300, c = d < dim ? corners[1][d] : 1e300;
    b.lo(d) = std::min(a, c);
    b.hi(d) = std::max(a, c);
  }
  return b;
}

void check_name(KeyReader& r, const std::string& key, const std::string& name) {
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
          std::string::npos)
    r.error(key, "expected a name of letters, digits, '_' or '-', got '" + name + "'");
}

PdMaterial read_material(KeyReader& m, const PdSpec& s) {
  PdMaterial mat;
  mat.name = m.text("name");
  check_name(m, "name", mat.name);
  for (const auto& other : s.materials)
    if (other.name == mat.name) m.error("name", "another material is named '" + mat.name + "'");
  mat.E = m.positive("E");
  mat.density = m.positive("density");
  mat.bulk_modulus = m.positive("bulk_modulus", 0.0);
  mat.micromodulus = m.positive("micromodulus", 0.0);
  if (mat.bulk_modulus > 0.0 && mat.micromodulus > 0.0)
    m.error("micromodulus", "give 'micromodulus' or 'bulk_modulus', not both");
  if (mat.bulk_modulus > 0.0 && s.dimension != materials::PdDimension::Solid3D)
    m.error("bulk_modulus", "the micromodulus from the bulk modulus is a 3D formula");
  mat.fracture_energy = m.positive("fracture_energy", 0.0);
  mat.critical_stretch = m.positive("critical_stretch", 0.0);
  if (mat.fracture_energy > 0.0 && mat.critical_stretch > 0.0)
    m.error("critical_stretch", "give 'fracture_energy' or 'critical_stretch', not both");
  const std::string bond = m.choice("bond", {"pmb", "microplastic"}, "pmb");
  if (bond == "microplastic") {
    mat.yield_stretch = m.positive("yield_stretch");
  } else if (m.has("yield_stretch")) {
    m.error("yield_stretch", "a yield stretch needs bond: microplastic");
  }
  m.allow("yield_stretch");
  mat.alpha = m.number("alpha", 0.0);
  if (mat.alpha != 0.0 && mat.critical_stretch <= 0.0)
    m.error("alpha", "the LAMMPS alpha rule needs 'critical_stretch' (s00)");
  m.finish();
  return mat;
}

int find_material(KeyReader& r, const std::string& key, const PdSpec& s, const std::string& name) {
  for (std::size_t k = 0; k < s.materials.size(); ++k)
    if (s.materials[k].name == name) return static_cast<int>(k);
  std::string names;
  for (const auto& m : s.materials) names += (names.empty() ? "" : ", ") + m.name;
  r.error(key, "no material is named '" + name + "' (materials: " + names + ")");
}

int find_function(KeyReader& r, const std::string& key, const PdSpec& s) {
  if (!r.has(key)) {
    r.allow(key);
    return -1;
  }
  const std::string name = r.text(key);
  for (std::size_t k = 0; k < s.functions.size(); ++k)
    if (s.functions[k].name == name) return static_cast<int>(k);
  r.error(key, "no function is named '" + name + "'");
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
  if (c.has("box")) out.box = read_box3(c, "box", dim);
  c.allow("box");
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
    if (!out.box) c.error("box", "a prescribed motion needs the box of particles it acts on");
  } else if (c.has("traction")) {
    out.kind = PdCondition::Kind::Traction;
    out.value = read_point(c, "traction", dim);
    out.area = c.positive("area", 0.0);
    if (!out.box) c.error("box", "a traction needs the box of the loaded layer of particles");
  } else if (c.has("blast")) {
    out.kind = PdCondition::Kind::Blast;
    KeyReader b = c.map("blast");
    out.blast.tnt_mass = b.positive("tnt_mass");
    out.blast.surface_burst = b.choice("burst", {"surface", "free_air"}, "surface") == "surface";
    out.blast.charge = read_point(b, "charge_at", dim);
    out.blast.normal = read_point(b, "normal", dim);
    if (!(out.blast.normal.norm() > 0.0)) b.error("normal", "expected a non-zero vector");
    out.blast.normal.normalize();
    b.finish();
    if (!out.box) c.error("box", "a blast load needs the box of the loaded layer of particles");
  } else {
    out.kind = PdCondition::Kind::BodyForce;
    out.value = read_point(c, "body_force", dim);
  }
  for (const char* k : kinds) c.allow(k);
  out.function = find_function(c, "function", s);
  c.finish();
  return out;
}

} // namespace

PdSpec parse_pd(KeyReader& r, const std::string& base_dir) {
  PdSpec s;
  {
    KeyReader m = r.map("model");
    const std::string type = m.choice("type", {"solid_3d", "plane_stress", "plane_strain"}, "");
    s.dimension = type == "solid_3d"       ? materials::PdDimension::Solid3D
                  : type == "plane_stress" ? materials::PdDimension::PlaneStress
                                           : materials::PdDimension::PlaneStrain;
    s.thickness = m.positive("thickness", 1.0);
    if (s.dimension == materials::PdDimension::Solid3D && m.has("thickness"))
      m.error("thickness", "a 3D body has no thickness");
    m.finish();
  }
  const int dim = s.dimension == materials::PdDimension::Solid3D ? 3 : 2;
  if (dim == 3) {
    KeyReader g = r.map("geometry");
    KeyReader b = g.map("box");
    const Vec3d origin = b.has("origin") ? read_point(b, "origin", 3) : Vec3d(0, 0, 0);
    b.allow("origin");
    const Vec3d size = read_point(b, "size", 3);
    if (size.minCoeff() <= 0.0) b.error("size", "expected positive extents");
    b.finish();
    g.finish();
    s.box = Box3{origin, origin + size};
  } else {
    r.allow("geometry"); // read by the caller (rectangle, polygon, holes)
  }

  for (KeyReader& m : r.map_list("materials")) s.materials.push_back(read_material(m, s));
  if (s.materials.empty()) r.error("materials", "at least one material is required");
  for (KeyReader& i : r.map_list("interfaces")) {
    PdInterface f;
    const YAML::Node names = i.raw("materials");
    if (!names.IsSequence() || names.size() != 2)
      i.error("materials", "expected the two material names [a, b]");
    f.a = names[0].as<std::string>();
    f.b = names[1].as<std::string>();
    find_material(i, "materials", s, f.a);
    find_material(i, "materials", s, f.b);
    f.base = i.text("base", f.a);
    find_material(i, "base", s, f.base);
    f.yield_stretch_factor = i.positive("yield_stretch_factor", 1.0);
    f.critical_stretch_factor = i.positive("critical_stretch_factor", 1.0);
    i.finish();
    s.interfaces.push_back(f);
  }

  {
    KeyReader d = r.map("discretisation");
    s.spacing = d.positive("spacing");
    s.horizon_factor = d.positive("horizon", 3.0);
    if (s.horizon_factor < 1.0 || s.horizon_factor > 10.0)
      d.error("horizon",
              "expected delta / spacing between 1 and 10, got " + detail::concat(s.horizon_factor));
    s.volume_correction = d.choice("volume_correction", {"exact", "linear", "none"}, "exact");
    const std::string surface = d.choice("surface_correction", {"none", "energy"}, "none");
    s.surface_correction = surface == "energy";
    d.finish();
  }
  for (KeyReader& g : r.map_list("regions")) {
    PdRegion reg;
    reg.material = g.text("material");
    find_material(g, "material", s, reg.material);
    reg.box = read_box3(g, "box", dim);
    g.finish();
    s.regions.push_back(reg);
  }
  for (KeyReader& g : r.map_list("notches")) {
    s.removed.push_back(read_box3(g, "box", dim));
    g.finish();
  }
  for (KeyReader& c : r.map_list("cracks")) {
    PdCrack k;
    k.a = read_point(c, "from", dim);
    k.b = read_point(c, "to", dim);
    if (dim == 3) k.c = read_point(c, "to2", dim);
    c.allow("to2");
    c.finish();
    s.cracks.push_back(k);
  }
  for (KeyReader& v : r.map_list("initial_velocity")) {
    PdSpec::InitialVelocity iv;
    if (v.has("box")) iv.box = read_box3(v, "box", dim);
    v.allow("box");
    iv.value = read_point(v, "value", dim);
    v.finish();
    s.initial_velocities.push_back(iv);
  }
  for (KeyReader& f : r.map_list("functions")) s.functions.push_back(read_function(f, base_dir, s));
  for (KeyReader& c : r.map_list("boundary")) s.conditions.push_back(read_condition(c, s, dim));
  for (KeyReader& k : r.map_list("impactors")) {
    PdImpactor imp;
    imp.name = k.text("name");
    check_name(k, "name", imp.name);
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
    imp.fixed = k.choice("motion", {"free", "fixed"}, "free") == "fixed";
    if (imp.fixed) {
      if (k.has("mass") || k.has("velocity"))
        k.error("motion", "a fixed impactor (a support) has no mass or velocity");
      k.allow("mass");
      k.allow("velocity");
    } else {
      imp.mass = k.positive("mass");
      imp.velocity = read_point(k, "velocity", dim);
    }
    imp.position = read_point(k, "position", dim);
    if (imp.velocity.norm() == 0.0 && !imp.sphere)
      k.error("velocity",
              "a flat impactor needs a velocity: its direction is the impact direction");
    k.finish();
    s.impactors.push_back(imp);
  }
  {
    KeyReader t = r.map("time");
    s.end_time = t.positive("end");
    s.dt = t.positive("dt", 0.0);
    s.safety = t.positive("safety", 0.8);
    if (s.safety > 1.0)
      t.error("safety", "expected a safety factor in (0, 1], got " + detail::concat(s.safety));
    t.finish();
  }
  if (auto o = r.optional_map("output")) {
    s.history_interval = o->positive("history_interval", 0.0);
    s.fields_interval = o->positive("fields_interval", 0.0);
    for (KeyReader& g : o->map_list("gauges")) {
      PdGauge gauge;
      gauge.name = g.text("name");
      check_name(g, "name", gauge.name);
      gauge.at = read_point(g, "at", dim);
      g.finish();
      s.gauges.push_back(gauge);
    }
    if (auto c = o->optional_map("crack")) {
      s.crack.enabled = true;
      s.crack.threshold = c->positive("damage_threshold", 0.38);
      if (s.crack.threshold >= 1.0) c->error("damage_threshold", "expected a value in (0, 1)");
      s.crack.origin = read_point(*c, "origin", dim);
      s.crack.direction = read_point(*c, "direction", dim);
      if (s.crack.direction.norm() == 0.0) c->error("direction", "expected a nonzero direction");
      s.crack.direction.normalize();
      c->finish();
    }
    o->finish();
  }
  return s;
}

} // namespace mf::io
