// The SPH part of a problem file (analysis: sph): dimension, materials with their equations of
// state, blocks of particles, detonation, viscosity, time and output. Every key is checked;
// errors name the key path.
#include "meshfree/io/hardening_read.hpp"
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/sph_read.hpp"
#include <algorithm>
#include <cmath>

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

sph::Eos read_eos(KeyReader& e) {
  sph::Eos eos;
  const std::string type =
      e.choice("type", {"ideal_gas", "jwl", "mie_gruneisen", "linear_polynomial"}, "");
  if (type == "ideal_gas") {
    eos.kind = sph::Eos::Kind::IdealGas;
    eos.ideal_gas.gamma = e.positive("gamma", 1.4);
    if (!(eos.ideal_gas.gamma > 1.0)) e.error("gamma", "expected a ratio of specific heats > 1");
  } else if (type == "jwl") {
    // Defaults: TNT, Dobratz & Crawford 1985 (materials/eos.hpp).
    eos.kind = sph::Eos::Kind::Jwl;
    materials::Jwl& j = eos.jwl;
    j.rho0 = e.positive("rho0", j.rho0);
    j.A = e.positive("A", j.A);
    j.B = e.positive("B", j.B);
    j.R1 = e.positive("R1", j.R1);
    j.R2 = e.positive("R2", j.R2);
    j.omega = e.positive("omega", j.omega);
    j.detonation_speed = e.positive("detonation_speed", j.detonation_speed);
    j.cj_pressure = e.positive("cj_pressure", j.cj_pressure);
    j.e0 = e.positive("detonation_energy", j.e0 * j.rho0) / j.rho0; // given per volume [J/m^3]
  } else if (type == "mie_gruneisen") {
    eos.kind = sph::Eos::Kind::MieGruneisen;
    materials::MieGruneisen& m = eos.mie_gruneisen;
    m.rho0 = e.positive("rho0");
    m.c0 = e.positive("c0");
    m.s = e.number("s");
    m.gamma0 = e.number("gamma0");
  } else {
    eos.kind = sph::Eos::Kind::LinearPolynomial;
    eos.linear_polynomial.rho0 = e.positive("rho0");
    const std::vector<double> c = e.numbers("c", 7);
    for (int k = 0; k < 7; ++k) eos.linear_polynomial.c[k] = c[k];
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
    if (auto st = m.optional_map("strength")) {
      // The deviatoric stress of a solid; the J2 return uses mu = G (E = 2G, nu = 0).
      mat.strength.enabled = true;
      mat.strength.shear_modulus = st->positive("shear_modulus");
      mat.strength.yield.E = 2.0 * mat.strength.shear_modulus;
      mat.strength.yield.nu = 0.0;
      if (st->has("yield_stress") || st->has("hardening")) {
        mat.strength.plastic = true;
        read_hardening(*st, mat.strength.yield);
      }
      st->finish();
    }
    m.finish();
    s.materials.push_back(mat);
  }
  if (s.materials.empty()) r.error("materials", "at least one material is required");
  for (KeyReader& b : r.map_list("blocks")) {
    SphBlock block;
    const int k = find_material(b, "material", s);
    block.material = s.materials[k].name;
    read_box(b, "box", dim, 0.0, block.lo, block.hi);
    for (int d = 0; d < dim; ++d)
      if (!(block.hi[d] > block.lo[d])) b.error("box", "the box is empty along an axis");
    block.spacing = b.positive("spacing");
    for (int d = 0; d < dim; ++d)
      if (block.spacing > block.hi[d] - block.lo[d])
        b.error("spacing", "larger than the box along an axis");
    const sph::Eos& eos = s.materials[k].eos;
    block.density = b.positive("density", eos.kind == sph::Eos::Kind::Jwl ? eos.jwl.rho0 : 0.0);
    if (!(block.density > 0.0)) b.error("density", "required value is missing");
    if (b.has("pressure") == b.has("energy") && eos.kind != sph::Eos::Kind::Jwl)
      b.error("energy", "give exactly one of 'energy' (J/kg) or 'pressure'");
    if (b.has("pressure")) {
      if (eos.kind != sph::Eos::Kind::IdealGas)
        b.error("pressure", "an initial pressure is turned into energy for an ideal gas only; "
                            "give 'energy'");
      block.energy = b.positive("pressure") / ((eos.ideal_gas.gamma - 1.0) * block.density);
    } else {
      block.energy = b.number("energy", eos.kind == sph::Eos::Kind::Jwl ? eos.jwl.e0 : 0.0);
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
  if (auto d = r.optional_map("detonation")) {
    s.detonation_point = read_point(*d, "point", dim);
    s.settings.burn_width = d->positive("burn_width", s.settings.burn_width);
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
