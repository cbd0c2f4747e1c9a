// The SPH part of a problem file (analysis: sph): dimension, materials with their equations of
// state, blocks of particles, detonation, viscosity, time and output. Every key is checked;
// errors name the key path.
#include "meshfree/io/hardening_read.hpp"
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/sph_read.hpp"
#include <algorithm>
#include <cmath>
#include <variant>

namespace mf::io {

namespace {

std::array<double, 3> read_point(KeyReader& r, const std::string& key, int dim) {
  const std::vector<double> v = r.numbers(key, dim);
  std::array<double, 3> out{0, 0, 0};
  for (int d = 0; d < dim; ++d) out[d] = v[d];
  return out;
}

/// A box [[x0, ...], [x1, ...]] with `dim` coordinates per corner; axes beyond dim span
/// [-unused, unused].
void read_box(KeyReader& r, const std::string& key, int dim, double unused,
              std::array<double, 3>& lo, std::array<double, 3>& hi) {
  const auto corners = r.number_lists(key, dim);
  if (corners.size() != 2) r.error(key, "expected two corners [[x0, ...], [x1, ...]]");
  for (int d = 0; d < 3; ++d) {
    lo[d] = d < dim ? std::min(corners[0][d], corners[1][d]) : -unused;
    hi[d] = d < dim ? std::max(corners[0][d], corners[1][d]) : unused;
  }
}

/// A non-zero vector with `dim` components, scaled to unit length.
std::array<double, 3> read_unit_vector(KeyReader& r, const std::string& key, int dim) {
  std::array<double, 3> v = read_point(r, key, dim);
  const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(norm > 0.0)) r.error(key, "expected a non-zero vector");
  for (double& c : v) c /= norm;
  return v;
}

/// A table [[x0, y0], [x1, y1], ...] with strictly ascending x, as a piecewise-linear function.
materials::PiecewiseLinear read_table(KeyReader& r, const std::string& key, std::size_t at_least,
                                      bool positive_values) {
  materials::PiecewiseLinear t;
  const auto rows = r.number_lists(key, 2);
  if (rows.size() < at_least)
    r.error(key, "expected at least " + std::to_string(at_least) + " rows [x, y]");
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (k > 0 && !(rows[k][0] > rows[k - 1][0]))
      r.error(key, detail::concat("row ", k, ": the first column must increase (", rows[k][0],
                                  " after ", rows[k - 1][0], ")"));
    if (positive_values && !(rows[k][1] > 0.0))
      r.error(key, detail::concat("row ", k, ": expected a positive value, got ", rows[k][1]));
    t.x.push_back(rows[k][0]);
    t.y.push_back(rows[k][1]);
  }
  return t;
}

/// The Holmquist-Johnson-Cook constants; defaults: the 48 MPa concrete of the 1993 paper.
materials::Hjc read_hjc(KeyReader& h) {
  materials::Hjc m;
  m.A = h.positive("A", m.A);
  m.B = h.positive("B", m.B);
  m.N = h.positive("N", m.N);
  m.C = h.number("C", m.C);
  m.s_max = h.positive("s_max", m.s_max);
  m.fc = h.positive("fc", m.fc);
  m.T = h.positive("T", m.T);
  m.eps_dot0 = h.positive("eps_dot0", m.eps_dot0);
  m.D1 = h.positive("D1", m.D1);
  m.D2 = h.positive("D2", m.D2);
  m.eps_f_min = h.positive("eps_f_min", m.eps_f_min);
  m.rho0 = h.positive("rho0", m.rho0);
  m.P_crush = h.positive("P_crush", m.P_crush);
  m.mu_crush = h.positive("mu_crush", m.mu_crush);
  m.K1 = h.positive("K1", m.K1);
  m.K2 = h.number("K2", m.K2);
  m.K3 = h.number("K3", m.K3);
  m.P_lock = h.positive("P_lock", m.P_lock);
  m.mu_lock = h.positive("mu_lock", m.mu_lock);
  m.shear_modulus = h.positive("shear_modulus", m.shear_modulus);
  if (!(m.mu_lock > m.mu_crush)) h.error("mu_lock", "must exceed mu_crush");
  if (!(m.P_lock > m.P_crush)) h.error("P_lock", "must exceed P_crush");
  const double mu_grain = materials::hjc_grain_compression(m);
  if (!(mu_grain > m.mu_crush && mu_grain < m.mu_lock))
    h.error("K1", "the fully dense curve K1, K2, K3 does not reach P_lock between mu_crush and "
                  "mu_lock");
  h.finish();
  return m;
}

materials::EquationOfState read_eos(KeyReader& e) {
  materials::EquationOfState eos;
  const std::string type = e.choice(
      "type", {"ideal_gas", "jwl", "mie_gruneisen", "linear_polynomial", "compaction", "hjc"}, "");
  if (type == "ideal_gas") {
    materials::IdealGas g;
    g.gamma = e.positive("gamma", 1.4);
    if (!(g.gamma > 1.0)) e.error("gamma", "expected a ratio of specific heats > 1");
    eos = g;
  } else if (type == "jwl") {
    // Defaults: TNT, Dobratz & Crawford 1985 (materials/eos.hpp).
    materials::JwlExplosive x;
    materials::Jwl& j = x.jwl;
    j.rho0 = e.positive("rho0", j.rho0);
    j.A = e.positive("A", j.A);
    j.B = e.positive("B", j.B);
    j.R1 = e.positive("R1", j.R1);
    j.R2 = e.positive("R2", j.R2);
    j.omega = e.positive("omega", j.omega);
    j.detonation_speed = e.positive("detonation_speed", j.detonation_speed);
    j.cj_pressure = e.positive("cj_pressure", j.cj_pressure);
    j.e0 = e.positive("detonation_energy", j.e0 * j.rho0) / j.rho0; // given per volume [J/m^3]
    if (auto u = e.optional_map("unreacted")) {
      // The unreacted explosive's shock Hugoniot U_s = c0 + s u_p and Grueneisen gamma.
      materials::MieGruneisen unreacted;
      unreacted.rho0 = j.rho0;
      unreacted.c0 = u->positive("c0");
      unreacted.s = u->positive("s");
      unreacted.gamma0 = u->positive("gamma0");
      x.unreacted = unreacted;
      u->finish();
    }
    eos = x;
  } else if (type == "mie_gruneisen") {
    materials::MieGruneisen m;
    m.rho0 = e.positive("rho0");
    m.c0 = e.positive("c0");
    m.s = e.number("s");
    m.gamma0 = e.number("gamma0");
    eos = m;
  } else if (type == "compaction") {
    // Tabulated compaction (materials/geomaterials.hpp): [density, pressure] and
    // [density, sound speed] rows.
    materials::Compaction c;
    c.loading = read_table(e, "loading", 2, false);
    c.sound_speed = read_table(e, "sound_speed", 1, true);
    if (c.loading.y.front() != 0.0)
      e.error("loading", "the loading curve must start at zero pressure (the initial density)");
    for (std::size_t k = 1; k < c.loading.y.size(); ++k)
      if (!(c.loading.y[k] > c.loading.y[k - 1]))
        e.error("loading", "the pressure must increase with density");
    c.tensile_limit = e.number("tensile_limit", 0.0);
    if (c.tensile_limit < 0.0) e.error("tensile_limit", "expected a tension magnitude >= 0");
    eos = c;
  } else if (type == "hjc") {
    eos = materials::Hjc{}; // constants from the material's 'hjc' map
  } else {
    materials::LinearPolynomial l;
    l.rho0 = e.positive("rho0");
    const std::vector<double> c = e.numbers("c", 7);
    for (int k = 0; k < 7; ++k) l.c[k] = c[k];
    eos = l;
  }
  e.finish();
  return eos;
}

int find_material(KeyReader& r, const std::string& key, const SphSpec& s) {
  const std::string name = r.text(key);
  for (std::size_t k = 0; k < s.materials.size(); ++k)
    if (s.materials[k].name == name) return static_cast<int>(k);
  std::string names;
  for (const auto& m : s.materials) names += (names.empty() ? "" : ", ") + m.name;
  r.error(key, "no material is named '" + name + "' (materials: " + names + ")");
}

} // namespace

SphSpec parse_sph(KeyReader& r) {
  SphSpec s;
  {
    KeyReader m = r.map("model");
    s.dimension = m.integer("dimension", 0, 1, 3);
    s.smoothing = m.positive("smoothing", 1.5);
    s.settings.kernel =
        m.choice("kernel", {"cubic_spline", "wendland_c2"}, "cubic_spline") == "cubic_spline"
            ? kernels::SphKernel::CubicSpline
            : kernels::SphKernel::WendlandC2;
    s.settings.gradient_correction = m.choice("gradient_correction", {"off", "on"}, "off") == "on";
    if (s.smoothing < 1.0 || s.smoothing > 3.0)
      m.error("smoothing",
              "expected h / spacing between 1 and 3, got " + std::to_string(s.smoothing));
    m.finish();
  }
  const int dim = s.dimension;
  for (KeyReader& m : r.map_list("materials")) {
    sph::Material mat;
    mat.name = m.text("name");
    for (const auto& other : s.materials)
      if (other.name == mat.name) m.error("name", "another material is named '" + mat.name + "'");
    KeyReader e = m.map("eos");
    mat.eos = read_eos(e);
    materials::Hjc hjc;
    if (auto h = m.optional_map("hjc")) hjc = read_hjc(*h);
    if (std::holds_alternative<materials::Hjc>(mat.eos)) mat.eos = hjc;
    bool hjc_strength = false;
    if (auto st = m.optional_map("strength")) {
      // The deviatoric stress of a solid; the J2 return uses mu = G (E = 2G, nu = 0).
      const bool yield_given = st->has("yield_stress") || st->has("hardening");
      const std::string model = st->choice("model", {"elastic", "von_mises", "granular", "hjc"},
                                           yield_given ? "von_mises" : "elastic");
      if (model == "granular") {
        materials::GranularStrength granular;
        granular.yield = read_table(*st, "yield", 2, false);
        if (st->has("shear_modulus") == st->has("shear_modulus_table"))
          st->error("shear_modulus", "give exactly one of 'shear_modulus' or "
                                     "'shear_modulus_table' [[density, G], ...]");
        if (st->has("shear_modulus")) {
          granular.shear_modulus = {{0.0}, {st->positive("shear_modulus")}}; // a constant
        } else {
          granular.shear_modulus = read_table(*st, "shear_modulus_table", 1, true);
        }
        mat.strength = granular;
      } else if (model == "hjc") {
        hjc_strength = true;
        mat.strength = hjc;
      } else {
        const double G = st->positive("shear_modulus");
        if (model == "von_mises") {
          if (!yield_given) st->error("yield_stress", "required value is missing");
          materials::VonMises vm;
          vm.shear_modulus = G;
          vm.j2.E = 2.0 * G;
          vm.j2.nu = 0.0;
          read_hardening(*st, vm.j2);
          mat.strength = vm;
        } else {
          mat.strength = materials::ElasticShear{G};
        }
      }
      mat.failure_strain = st->positive("failure_strain", 0.0);
      if (st->has("failure_strain") && !(mat.failure_strain > 0.0))
        st->error("failure_strain", "expected a positive plastic strain");
      st->finish();
    }
    const bool hjc_eos = std::holds_alternative<materials::Hjc>(mat.eos);
    if (hjc_eos != hjc_strength)
      m.error(hjc_eos ? "strength" : "eos",
              "the HJC model needs both 'eos: {type: hjc}' and 'strength: {model: hjc}'");
    m.finish();
    s.materials.push_back(mat);
  }
  if (s.materials.empty()) r.error("materials", "at least one material is required");
  for (KeyReader& b : r.map_list("blocks")) {
    SphBlock block;
    const int k = find_material(b, "material", s);
    block.material = s.materials[k].name;
    if (b.has("box") == b.has("ring")) b.error("box", "give exactly one of 'box' or 'ring'");
    block.spacing = b.positive("spacing");
    if (b.has("ring")) {
      // A ring (2D): concentric circles of particles between the two radii.
      if (dim != 2) b.error("ring", "rings are available in 2D only");
      KeyReader g = b.map("ring");
      block.is_ring = true;
      block.ring.center = read_point(g, "center", dim);
      block.ring_inner_radius = g.positive("inner_radius");
      block.ring.radius = g.positive("outer_radius");
      if (!(block.ring.radius > block.ring_inner_radius))
        g.error("outer_radius", "must exceed inner_radius");
      if (block.spacing > block.ring.radius - block.ring_inner_radius)
        b.error("spacing", "larger than the ring's thickness");
      g.finish();
    } else {
      read_box(b, "box", dim, 0.0, block.lo, block.hi);
      for (int d = 0; d < dim; ++d)
        if (!(block.hi[d] > block.lo[d])) b.error("box", "the box is empty along an axis");
      for (int d = 0; d < dim; ++d)
        if (block.spacing > block.hi[d] - block.lo[d])
          b.error("spacing", "larger than the box along an axis");
    }
    if (auto c = b.optional_map("inside")) {
      // A round block: a disc in 2D, a cylinder along z in 3D.
      if (dim == 1) c->error("center", "'inside' needs 2D or 3D");
      SphCircle keep;
      const std::vector<double> at = c->numbers("center", 2);
      keep.center = {at[0], at[1], 0.0};
      keep.radius = c->positive("radius");
      c->finish();
      block.inside = keep;
    }
    for (KeyReader& c : b.map_list("holes")) {
      if (dim == 1) c.error("center", "holes need 2D or 3D");
      SphCircle hole;
      const std::vector<double> at = c.numbers("center", 2);
      hole.center = {at[0], at[1], 0.0};
      hole.radius = c.positive("radius");
      c.finish();
      block.holes.push_back(hole);
    }
    const materials::EquationOfState& eos = s.materials[k].eos;
    const auto* explosive = std::get_if<materials::JwlExplosive>(&eos);
    const auto* ideal_gas = std::get_if<materials::IdealGas>(&eos);
    const auto* hjc = std::get_if<materials::Hjc>(&eos);
    const auto* compaction = std::get_if<materials::Compaction>(&eos);
    double natural = 0.0; // the reference density of the equation of state, where it has one
    if (explosive) natural = explosive->jwl.rho0;
    if (hjc) natural = hjc->rho0;
    if (compaction) natural = compaction->loading.x.front();
    block.density = b.positive("density", natural);
    if (!(block.density > 0.0)) b.error("density", "required value is missing");
    const bool energy_free = compaction || hjc;
    if (energy_free && b.has("energy"))
      b.error("energy", "this equation of state does not depend on the internal energy");
    if (b.has("pressure") == b.has("energy") && !explosive && !energy_free)
      b.error("energy", "give exactly one of 'energy' (J/kg) or 'pressure'");
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
    block.fixed = b.choice("motion", {"free", "fixed"}, "free") == "fixed";
    if (block.fixed && b.has("velocity")) b.error("velocity", "a fixed block does not move");
    b.finish();
    s.blocks.push_back(block);
  }
  if (s.blocks.empty()) r.error("blocks", "at least one block of particles is required");
  for (KeyReader& l : r.map_list("loads")) {
    SphBlastLoad load;
    load.key_path = l.path();
    load.name = l.text("name");
    read_box(l, "box", dim, 1e300, load.lo, load.hi);
    KeyReader b = l.map("blast");
    load.tnt_mass = b.positive("tnt_mass");
    load.surface_burst = b.choice("burst", {"surface", "free_air"}, "surface") == "surface";
    load.charge = read_point(b, "charge_at", dim);
    load.normal = read_unit_vector(b, "normal", dim);
    load.clamp_below_range = b.choice("near_field", {"error", "clamp"}, "error") == "clamp";
    b.finish();
    l.finish();
    s.loads.push_back(load);
  }
  for (KeyReader& b : r.map_list("boundaries")) {
    SphTransmitting t;
    t.key_path = b.path();
    t.name = b.text("name");
    b.choice("type", {"transmitting"}, "");
    read_box(b, "box", dim, 1e300, t.lo, t.hi);
    t.normal = read_unit_vector(b, "normal", dim);
    b.finish();
    s.transmitting.push_back(t);
  }
  for (KeyReader& m : r.map_list("symmetry")) {
    sph::SymmetryPlane plane;
    const std::vector<std::string> axes{"x", "y", "z"};
    const std::string axis =
        m.choice("axis", std::vector<std::string>(axes.begin(), axes.begin() + dim), "");
    plane.axis = static_cast<int>(std::find(axes.begin(), axes.end(), axis) - axes.begin());
    plane.at = m.number("at");
    for (const auto& other : s.symmetry)
      if (other.axis == plane.axis) m.error("axis", "another symmetry plane is normal to " + axis);
    m.finish();
    s.symmetry.push_back(plane);
  }
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
    s.settings.burn_width = d->positive("burn_width", s.settings.burn_width);
    s.settings.ignition_compression =
        d->positive("ignition_compression", s.settings.ignition_compression);
    d->finish();
  }
  if (auto v = r.optional_map("viscosity")) {
    s.settings.alpha = v->number("alpha", 1.0);
    s.settings.beta = v->number("beta", 1.0);
    s.settings.phi = v->positive("phi", 0.1);
    if (s.settings.alpha < 0.0 || s.settings.beta < 0.0)
      v->error("alpha", "the viscosity coefficients must not be negative");
    v->finish();
  }
  if (auto a = r.optional_map("artificial_stress")) {
    s.settings.artificial_stress = a->positive("epsilon", 0.3);
    s.settings.artificial_stress_exponent = a->integer("exponent", 4, 1, 12);
    a->finish();
  }
  if (auto f = r.optional_map("interface")) {
    // The inter-material penalty force (sph/hydro.hpp, Settings::Penalty).
    sph::Settings::Penalty& pen = s.settings.penalty;
    pen.pressure = f->positive("penalty_pressure");
    pen.n1 = f->integer("n1", 12, 1, 32);
    pen.n2 = f->integer("n2", 6, 0, 31);
    pen.distance = f->positive("distance", 1.0);
    if (pen.n2 >= pen.n1) f->error("n2", "must be smaller than n1 for a repulsive force");
    if (pen.distance > 2.0) f->error("distance", "expected at most 2 particle spacings");
    f->finish();
  }
  {
    KeyReader t = r.map("time");
    s.end_time = t.positive("end");
    s.settings.courant = t.positive("courant", 0.3);
    if (s.settings.courant > 1.0) t.error("courant", "expected a Courant number <= 1");
    t.finish();
  }
  if (auto o = r.optional_map("output")) {
    s.history_interval = o->positive("history_interval", 0.0);
    s.fields_interval = o->positive("fields_interval", 0.0);
    for (KeyReader& g : o->map_list("gauges")) {
      SphGauge gauge;
      gauge.name = g.text("name");
      gauge.at = read_point(g, "at", dim);
      g.finish();
      s.gauges.push_back(gauge);
    }
    o->finish();
  }
  return s;
}

} // namespace mf::io
