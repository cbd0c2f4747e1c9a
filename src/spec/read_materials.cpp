// The `materials:` list: elastic constants, density, plasticity, equation of state, strength,
// HJC constants and peridynamic bond parameters of each named material. Every key is checked;
// errors name the key path.
#include "meshfree/spec/spec_read.hpp"
#include <cmath>
#include <variant>

namespace mf::spec {

namespace {

/// A table whose yield stress falls somewhere softens the material: like a Voce law's, taken only
/// when the hardening map says softening: true. Its last segment may not fall even then: the
/// yield stress goes on along it past the last point and would reach zero.
void check_table_softening(KeyReader& h, const materials::TableHardening& t) {
  const std::size_t n = t.alpha.size();
  const bool softening = h.choice("softening", {"false", "true"}, "false") == "true";
  for (std::size_t k = 1; k < n; ++k)
    if (t.sigma[k] < t.sigma[k - 1] && !softening)
      h.error("points", detail::concat("the yield stress falls from ", t.sigma[k - 1], " to ",
                                       t.sigma[k], " at equivalent plastic strain ", t.alpha[k],
                                       ": a softening law; give softening: true if that is meant"));
  const double slope = (t.sigma[n - 1] - t.sigma[n - 2]) / (t.alpha[n - 1] - t.alpha[n - 2]);
  if (slope < 0.0)
    h.error("points", detail::concat("the last segment falls, and the yield stress goes on along "
                                     "it past the last point (zero at equivalent plastic strain ",
                                     t.alpha[n - 1] - t.sigma[n - 1] / slope,
                                     "); end the table with a segment that does not fall"));
}

} // namespace

void read_hardening(KeyReader& p, materials::J2Parameters& j) {
  const bool has_yield = p.has("yield_stress");
  std::string type = "perfect";
  std::optional<KeyReader> h;
  if (p.has("hardening")) {
    YAML::Node n = p.raw("hardening");
    if (n.IsScalar()) {
      type = n.Scalar();
      if (type != "perfect")
        p.error("hardening", "'" + type +
                                 "' needs parameters: give a map {type: linear|voce|swift|table, "
                                 "...}, or 'perfect'");
    } else {
      h.emplace(n, p.path_of("hardening"));
      type = h->choice("type", {"perfect", "linear", "voce", "swift", "table"}, "");
    }
  }
  const bool defines_yield = type == "swift" || type == "table";
  if (defines_yield && has_yield)
    p.error("yield_stress", "the " + type + " law sets the initial yield stress itself; remove it");
  if (!defines_yield) j.sigma0 = p.positive("yield_stress");
  p.allow("yield_stress");
  const auto non_negative = [](KeyReader& k, const std::string& key) {
    const double v = k.number(key);
    if (v < 0.0) k.error(key, "expected a number >= 0, got " + detail::concat(v));
    return v;
  };
  if (type == "linear") {
    j.hardening = materials::LinearHardening{non_negative(*h, "H")};
  } else if (type == "voce") {
    materials::VoceHardening v;
    v.H = non_negative(*h, "H");
    v.sigma_inf = h->positive("sigma_inf");
    v.delta = h->positive("delta");
    // sigma_inf below the initial yield stress makes the saturation term soften the material
    // (the yield stress falls as it flows): a slip of units or of a digit more often than a
    // material's law, so it is taken only when the file says it means it.
    const bool softening = h->choice("softening", {"false", "true"}, "false") == "true";
    if (v.sigma_inf < j.sigma0 && !softening)
      h->error("sigma_inf", "is below the yield stress " + detail::concat(j.sigma0) +
                                ": a softening law; give softening: true if that is meant");
    j.hardening = v;
  } else if (type == "swift") {
    materials::SwiftHardening w;
    w.K = h->positive("K");
    w.eps0 = h->positive("eps0");
    w.n = h->positive("n");
    if (w.n > 1.0) h->error("n", "expected an exponent in (0, 1], got " + detail::concat(w.n));
    j.hardening = w;
    j.sigma0 = w.K * std::pow(w.eps0, w.n);
  } else if (type == "table") {
    materials::TableHardening t;
    for (const Vec2& pt : h->vec2_list("points")) {
      t.alpha.push_back(pt.x());
      t.sigma.push_back(pt.y());
    }
    if (t.alpha.size() < 2)
      h->error("points", "expected at least two [equivalent plastic strain, yield stress] pairs");
    if (t.alpha.front() != 0.0)
      h->error("points", "the first point must be at equivalent plastic strain 0, got " +
                             detail::concat(t.alpha.front()));
    for (std::size_t k = 0; k < t.alpha.size(); ++k) {
      if (k > 0 && !(t.alpha[k] > t.alpha[k - 1]))
        h->error("points", "equivalent plastic strains must increase, got " +
                               detail::concat(t.alpha[k - 1]) + " then " +
                               detail::concat(t.alpha[k]));
      if (!(t.sigma[k] > 0.0))
        h->error("points", "yield stresses must be positive, got " + detail::concat(t.sigma[k]));
    }
    check_table_softening(*h, t);
    j.sigma0 = t.sigma.front();
    j.hardening = t;
  }
  if (h) h->finish();
}

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

namespace {

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

/// `strength:`; shear_modulus_key: the material gives 'shear_modulus' itself (not derived from
/// E and nu, which a Galerkin stage of the same material needs beside a granular table).
StrengthSpec read_strength(KeyReader& st, const MaterialSpec& m, bool shear_modulus_key) {
  StrengthSpec s;
  const std::string model = st.choice("model", {"j2", "granular", "hjc"}, "j2");
  if (model == "granular") {
    s.model = StrengthSpec::Model::Granular;
    s.granular.yield = read_table(st, "yield", 2, false);
    const bool table = st.has("shear_modulus_table");
    if ((shear_modulus_key && table) || !(m.shear_modulus > 0.0 || table))
      st.error("shear_modulus_table", "give exactly one of the material's 'shear_modulus' or "
                                      "'strength.shear_modulus_table' [[density, G], ...]");
    if (st.has("shear_modulus_table"))
      s.granular.shear_modulus = read_table(st, "shear_modulus_table", 1, true);
    st.allow("shear_modulus_table");
  } else if (model == "hjc") {
    s.model = StrengthSpec::Model::Hjc;
  }
  s.failure_strain = st.positive("failure_strain", 0.0);
  st.finish();
  return s;
}

BondSpec read_bond(KeyReader& m) {
  BondSpec b;
  b.micromodulus = m.positive("micromodulus", 0.0);
  b.fracture_energy = m.positive("fracture_energy", 0.0);
  b.critical_stretch = m.positive("critical_stretch", 0.0);
  if (b.fracture_energy > 0.0 && b.critical_stretch > 0.0)
    m.error("critical_stretch", "give 'fracture_energy' or 'critical_stretch', not both");
  const std::string law = m.choice("law", {"pmb", "microplastic", "lps", "eps"}, "pmb");
  b.microplastic = law == "microplastic";
  b.lps = law == "lps" || law == "eps";
  if (law == "eps") {
    b.yield_stress = m.positive("yield_stress");
  } else if (m.has("yield_stress")) {
    m.error("yield_stress", "a yield stress belongs to law: eps");
  }
  m.allow("yield_stress");
  if (b.lps) {
    const std::string f =
        m.choice("influence", {"inverse_length", "constant", "gaussian"}, "inverse_length");
    b.influence = f == "constant"   ? materials::Influence::Constant
                  : f == "gaussian" ? materials::Influence::Gaussian
                                    : materials::Influence::InverseLength;
    if (b.micromodulus > 0.0)
      m.error("micromodulus", "law: lps takes its constants from the material's E and nu (or "
                              "bulk_modulus and shear_modulus), not a micromodulus");
  } else if (m.has("influence")) {
    m.error("influence", "an influence function belongs to law: lps");
  }
  m.allow("influence");
  if (b.microplastic) {
    b.yield_stretch = m.positive("yield_stretch");
  } else if (m.has("yield_stretch")) {
    m.error("yield_stretch", "a yield stretch needs law: microplastic");
  }
  m.allow("yield_stretch");
  b.alpha = m.number("alpha", 0.0);
  if (b.alpha != 0.0 && b.critical_stretch <= 0.0)
    m.error("alpha", "the LAMMPS alpha rule needs 'critical_stretch' (s00)");
  m.finish();
  return b;
}

materials::J2Parameters read_j2(KeyReader& p, const MaterialSpec& mat) {
  materials::J2Parameters j;
  j.E = mat.E;
  j.nu = mat.nu;
  read_hardening(p, j);
  j.H_kinematic = p.number("kinematic_modulus", 0.0);
  if (j.H_kinematic < 0.0)
    p.error("kinematic_modulus", "expected a number >= 0, got " + detail::concat(j.H_kinematic));
  return j;
}

/// An angle in degrees in [0, 90), returned in radians; required without a fallback.
double read_angle(KeyReader& p, const std::string& key,
                  std::optional<double> fallback_degrees = std::nullopt) {
  const double degrees = fallback_degrees ? p.number(key, *fallback_degrees) : p.number(key);
  if (!(degrees >= 0.0 && degrees < 90.0))
    p.error(key, "expected an angle in degrees in [0, 90), got " + detail::concat(degrees));
  return degrees * M_PI / 180.0;
}

/// Drucker-Prager from Mohr-Coulomb's cohesion and angles, matched as `match` says.
materials::DruckerPragerParameters read_drucker_prager(KeyReader& p, const MaterialSpec& mat) {
  materials::DruckerPragerParameters d;
  d.E = mat.E;
  d.nu = mat.nu;
  d.cohesion = p.number("cohesion");
  if (!(d.cohesion >= 0.0))
    p.error("cohesion", "expected a number >= 0, got " + detail::concat(d.cohesion));
  d.hardening = p.number("cohesion_hardening", 0.0);
  if (d.hardening < 0.0)
    p.error("cohesion_hardening", "expected a number >= 0, got " + detail::concat(d.hardening));
  const std::string match = p.choice("match", {"plane_strain", "outer", "inner"}, "plane_strain");
  const auto how = match == "outer"   ? materials::MohrCoulombMatch::Outer
                   : match == "inner" ? materials::MohrCoulombMatch::Inner
                                      : materials::MohrCoulombMatch::PlaneStrain;
  const double phi = read_angle(p, "friction_angle");
  const double psi = read_angle(p, "dilation_angle", phi * 180.0 / M_PI);
  if (psi > phi)
    p.error("dilation_angle", detail::concat("expected at most the friction angle ",
                                             phi * 180.0 / M_PI, ", got ", psi * 180.0 / M_PI));
  const materials::ConeConstants cone = materials::mohr_coulomb_cone(phi, how);
  d.eta = cone.eta;
  d.xi = cone.xi;
  d.eta_bar = materials::mohr_coulomb_cone(psi, how).eta;
  if (d.cohesion == 0.0 && phi == 0.0)
    p.error("friction_angle", "a soil without cohesion needs a friction angle above 0");
  if (p.has("tension_cutoff")) {
    d.tension_cutoff = p.number("tension_cutoff");
    const double apex = materials::apex_pressure(d, d.cohesion);
    if (!(d.tension_cutoff >= 0.0 && d.tension_cutoff < apex))
      p.error("tension_cutoff",
              detail::concat("expected a mean stress in [0, ", apex,
                             ") (the cone's apex, xi c / eta), got ", d.tension_cutoff));
  }
  p.allow("tension_cutoff");
  return d;
}

/// `plasticity:` of a material: the model by name (j2 by default) and its parameters.
materials::ConstitutiveModel read_plasticity(KeyReader& p, const MaterialSpec& mat) {
  const std::string model = p.choice("model", {"j2", "drucker_prager"}, "j2");
  materials::ConstitutiveModel out;
  if (model == "drucker_prager")
    out = read_drucker_prager(p, mat);
  else
    out = read_j2(p, mat);
  p.finish();
  return out;
}

MaterialSpec read_material(KeyReader& m) {
  MaterialSpec mat;
  mat.key_path = m.path();
  mat.name = m.text("name");
  check_name(m, "name", mat.name);
  mat.E = m.positive("E", 0.0);
  mat.has_nu = m.has("nu");
  mat.nu = m.number("nu", 0.0);
  if (mat.has_nu && !(mat.nu > -1.0 && mat.nu < 0.5))
    m.error("nu", "expected a Poisson's ratio in (-1, 0.5), got " + std::to_string(mat.nu));
  mat.shear_modulus = m.positive("shear_modulus", 0.0);
  if (mat.shear_modulus > 0.0 && mat.has_nu && m.has("E"))
    m.error("shear_modulus", "give two of E, nu and shear_modulus, not all three");
  if (mat.shear_modulus > 0.0 && m.has("E")) {
    // nu from E and G (isotropic elasticity: G = E / (2 (1 + nu))).
    mat.has_nu = true;
    mat.nu = mat.E / (2.0 * mat.shear_modulus) - 1.0;
    if (!(mat.nu > -1.0 && mat.nu < 0.5))
      m.error("shear_modulus", "E and G give a Poisson's ratio outside (-1, 0.5)");
  } else if (mat.shear_modulus == 0.0 && mat.E > 0.0 && mat.has_nu) {
    mat.shear_modulus = mat.E / (2.0 * (1.0 + mat.nu));
  }
  mat.bulk_modulus = m.positive("bulk_modulus", 0.0);
  mat.density = m.positive("density", 0.0);
  if (auto p = m.optional_map("plasticity")) mat.plasticity = read_plasticity(*p, mat);
  if (auto e = m.optional_map("eos")) mat.eos = read_eos(*e);
  if (auto h = m.optional_map("hjc")) mat.hjc = read_hjc(*h);
  if (auto st = m.optional_map("strength"))
    mat.strength = read_strength(*st, mat, m.has("shear_modulus"));
  const bool hjc_eos = mat.eos && std::holds_alternative<materials::Hjc>(*mat.eos);
  const bool hjc_strength = mat.strength && mat.strength->model == StrengthSpec::Model::Hjc;
  if (hjc_eos != hjc_strength)
    m.error(hjc_eos ? "strength" : "eos",
            "the HJC model needs both 'eos: {type: hjc}' and 'strength: {model: hjc}'");
  if (hjc_eos && !mat.hjc) mat.hjc = materials::Hjc{}; // the constants' defaults
  if (hjc_eos) mat.eos = *mat.hjc;
  if (auto b = m.optional_map("bond")) mat.bond = read_bond(*b);
  m.finish();
  return mat;
}

} // namespace

std::vector<MaterialSpec> read_materials(KeyReader& r) {
  std::vector<MaterialSpec> out;
  for (KeyReader& m : r.map_list("materials")) {
    out.push_back(read_material(m));
    for (std::size_t k = 0; k + 1 < out.size(); ++k)
      if (out[k].name == out.back().name)
        m.error("name", "another material is named '" + out.back().name + "'");
  }
  if (out.empty()) r.error("materials", "at least one material is required");
  return out;
}

int find_material(KeyReader& r, const std::string& key, const std::vector<MaterialSpec>& list,
                  const std::string& name) {
  for (std::size_t k = 0; k < list.size(); ++k)
    if (list[k].name == name) return static_cast<int>(k);
  std::string names;
  for (const auto& m : list) names += (names.empty() ? "" : ", ") + m.name;
  r.error(key, "no material is named '" + one_line(name) + "' (materials: " + names + ")");
}

void material_error(const MaterialSpec& m, const std::string& part, const std::string& message) {
  fail(m.key_path, ".", part, ": ", message);
}

} // namespace mf::spec
