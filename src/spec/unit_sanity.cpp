// Unit-sanity warnings: each value is converted to SI with the declared unit system and compared
// with the range real solids and loads span. The ranges are wide (a slip of units moves a value
// by 10^3 to 10^12, a factor of g by about 10), so a warning means a likely slip, not an error.
#include "meshfree/spec/unit_sanity.hpp"
#include "meshfree/core/log.hpp"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace mf::spec {
namespace {

// Plausible SI ranges (README "Units"). Moduli: soft foams and rubbers (about 1e5 Pa) up to
// diamond (about 1.1e12 Pa); densities: gases at ambient pressure (air 1.2 kg/m^3) up to
// osmium (22,590 kg/m^3); yield stresses: soil cohesion (kPa) up to the strongest steels
// (about 5 GPa); elastic wave speeds sqrt(M / rho): soft rubber (tens of m/s) up to diamond
// (18 km/s).
struct Range {
  double lo, hi;
  const char* unit;
};
constexpr Range kModulus{1e4, 1e13, "Pa"};
constexpr Range kDensity{0.05, 3e4, "kg/m^3"};
constexpr Range kYield{1e3, 1e10, "Pa"};
constexpr Range kLoad{0.0, 1e11, "Pa"};      // a traction or pressure (blasts reach GPa)
constexpr Range kGravity{0.1, 1e3, "m/s^2"}; // the Moon to a geotechnical centrifuge
constexpr Range kWaveSpeed{10.0, 3e4, "m/s"};
constexpr Range kStep{1e-11, 1e-1, "s"}; // spacing / wave speed of an explicit run
constexpr Range kBodySize{1e-4, 1e4, "m"}; // a tenth of a millimetre to 10 km across
constexpr double kMaxYieldStrain = 0.1;  // sigma_y / E of metals, polymers, rock: < 0.05
constexpr double kMaxLoadStrain = 1.0;   // load / E: a strain beyond 100%
constexpr double kMaxSteps = 1e9;        // end time / step

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string num(double v) {
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

/// Collects warnings, each text once (stages share their materials).
class Report {
public:
  explicit Report(const UnitSystem& u, const std::string& units) : u_(u), units_(units) {}

  void check(const std::string& key, double value, double to_si, const Range& r, const char* what) {
    const double si = std::abs(value) * to_si;
    if (value == 0.0 || (si >= r.lo && si <= r.hi)) return;
    add(key + " = " + num(value) + " is " + num(si) + " " + r.unit + " in the declared units ('" +
        units_ + "'): " + what + " usually lie within " + num(r.lo) + ".." + num(r.hi) + " " +
        r.unit + "; check the value's units");
  }
  void add(const std::string& text) {
    if (seen_.insert(text).second) lines_.push_back(text);
  }
  const UnitSystem& units() const { return u_; }
  const std::string& name() const { return units_; }
  std::vector<std::string> lines() const { return lines_; }

private:
  UnitSystem u_;
  std::string units_;
  std::set<std::string> seen_;
  std::vector<std::string> lines_;
};

/// The P-wave modulus of a material when it has enough constants: E (a bar's wave, the lower
/// bound), or K + 4G/3; 0 when none is given.
double wave_modulus(const MaterialSpec& m) {
  if (m.E > 0.0) return m.E;
  if (m.bulk_modulus > 0.0) return m.bulk_modulus + 4.0 * m.shear_modulus / 3.0;
  return m.shear_modulus;
}

void check_material(Report& r, const MaterialSpec& m) {
  const UnitSystem& u = r.units();
  r.check(m.key_path + ".E", m.E, u.stress(), kModulus, "Young's moduli");
  // A shear modulus derived from E and nu is not a second cause of E's warning.
  const bool derived = m.E > 0.0 && std::abs(m.shear_modulus - m.E / (2.0 * (1.0 + m.nu))) <=
                                        1e-12 * m.shear_modulus;
  if (!derived)
    r.check(m.key_path + ".shear_modulus", m.shear_modulus, u.stress(), kModulus, "shear moduli");
  r.check(m.key_path + ".bulk_modulus", m.bulk_modulus, u.stress(), kModulus, "bulk moduli");
  r.check(m.key_path + ".density", m.density, u.density(), kDensity, "densities");
  const double modulus = m.E > 0.0 ? m.E : m.shear_modulus * 2.0 * (1.0 + m.nu);
  const materials::StrengthInput strength =
      m.plasticity ? materials::strength_input(*m.plasticity) : materials::StrengthInput{};
  const double sy = strength.value;
  if (sy > 0.0) {
    const std::string key = m.key_path + ".plasticity." + strength.key;
    r.check(key, sy, u.stress(), kYield, "yield stresses");
    if (modulus > 0.0 && sy / modulus > kMaxYieldStrain)
      r.add(key + " = " + num(sy) + " is " + num(sy / modulus) + " of E = " + num(modulus) +
            ": yield strains of solids are below " + num(kMaxYieldStrain) +
            "; are both in the same units?");
  }
  const double M = wave_modulus(m);
  if (M > 0.0 && m.density > 0.0) {
    const double c = std::sqrt(M / m.density);
    r.check(m.key_path + " wave speed sqrt(modulus / density)", c, u.speed(), kWaveSpeed,
            "elastic wave speeds");
  }
}

double stiffest(const ProblemSpec& p) {
  double E = 0.0;
  for (const auto& m : p.materials) E = std::max(E, wave_modulus(m));
  return E;
}

void check_load(Report& r, const std::string& key, double load, double E) {
  r.check(key, load, r.units().stress(), kLoad, "tractions and pressures");
  if (E > 0.0 && std::abs(load) / E > kMaxLoadStrain)
    r.add(key + " = " + num(load) + " is " + num(std::abs(load) / E) +
          " times the stiffest modulus " + num(E) +
          ": a strain far beyond 1; are the load and the modulus in the same units?");
}

void check_loads(Report& r, const ProblemSpec& p) {
  const double E = stiffest(p);
  double g = 0.0;
  if (const GalerkinSpec* galerkin = std::get_if<GalerkinSpec>(&p.part)) {
    for (const auto& b : galerkin->boundary) {
      if (b.loads && !b.traction_from_exact)
        check_load(r, b.key_path + ".traction", b.traction.norm(), E);
      if (b.pressure_load) check_load(r, b.key_path + ".pressure", b.pressure, E);
    }
    g = galerkin->gravity.norm();
  }
  if (const SphSpec* sph = std::get_if<SphSpec>(&p.part)) {
    for (const auto& t : sph->tractions)
      check_load(r, t.key_path + ".traction", t.traction.norm(), E);
    g = sph->gravity.norm();
  }
  if (const PdSpec* pd = std::get_if<PdSpec>(&p.part))
    for (const auto& c : pd->conditions)
      if (c.kind == PdCondition::Kind::Traction)
        check_load(r, c.key_path + ".traction", c.value.norm(), E);
  r.check("gravity", g, r.units().acceleration(), kGravity, "gravitational accelerations");
}

/// The fastest elastic wave of the body's materials (SPH regions carry their own density).
double fastest_wave(Report& r, const ProblemSpec& p) {
  double c = 0.0;
  auto take = [&](const MaterialSpec& m, double density) {
    if (wave_modulus(m) > 0.0 && density > 0.0)
      c = std::max(c, std::sqrt(wave_modulus(m) / density));
  };
  for (const auto& m : p.materials) take(m, m.density);
  if (p.is_sph())
    for (std::size_t k = 0; k < p.sph().regions.size(); ++k) {
      const SphRegion& reg = p.sph().regions[k];
      r.check("regions[" + std::to_string(k) + "].density", reg.density, r.units().density(),
              kDensity, "densities");
      take(p.sph().materials[reg.material], reg.density);
    }
  return c;
}

/// The explicit step, spacing / c of the fastest material, and the number of steps to the end.
void check_step(Report& r, const ProblemSpec& p) {
  double spacing = 0.0, end = 0.0;
  std::string prefix; // the stage's key path in a staged run
  if (p.is_sph()) {
    end = p.sph().end_time, prefix = p.sph().key_prefix;
    for (const auto& reg : p.sph().regions)
      spacing = spacing > 0.0 ? std::min(spacing, reg.spacing) : reg.spacing;
  } else if (p.is_pd()) {
    end = p.pd().end_time, spacing = p.pd().spacing, prefix = p.pd().key_prefix;
  }
  const double c = fastest_wave(r, p);
  if (spacing <= 0.0 || c <= 0.0) return;
  const double dt = spacing / c;
  r.check("the stable time step, about spacing / wave speed,", dt, r.units().time, kStep,
          "explicit time steps");
  if (end / dt > kMaxSteps)
    r.add(prefix + "time.end = " + num(end) + " is about " + num(end / dt) + " steps of " +
          num(dt) + " (spacing / wave speed): check the end time's units");
}

/// A body's extent (its largest side) at `key`: a drawing in mm read into a model in m, or a
/// `scale` given twice, makes a body a thousand or a million times too large or too small.
void check_size(Report& r, const std::string& key, double extent) {
  const double si = extent * r.units().length;
  if (si >= kBodySize.lo && si <= kBodySize.hi) return;
  r.add(key + ": the body is " + num(extent) + " across, " + num(si) +
        " m in the declared units ('" + r.name() + "'): bodies usually lie within " +
        num(kBodySize.lo) + ".." + num(kBodySize.hi) +
        " m; check the drawing's units and its scale");
}

/// The extent of the body an implicit analysis reads from `geometry:` (built in or from a file),
/// and each SPH region's.
void check_sizes(Report& r, const ProblemSpec& p, bool front) {
  // The plane body of `geometry:`: the analysis's own, a staged run's preload's, a plane
  // peridynamic body's.
  const ProblemSpec* body = &p;
  if (const StagedSpec* staged = std::get_if<StagedSpec>(&p.part)) body = &staged->stages.front();
  if (front && (body->is_galerkin() || body->is_solid() || (body->is_pd() && p.dimension == 2)))
    check_size(r, "geometry", body->domain.bounds().size().maxCoeff());
  if (!p.is_sph()) return;
  for (const SphRegion& reg : p.sph().regions) {
    const Region& g = reg.region;
    const std::string key = p.sph().key_prefix + reg.key_path;
    if (g.ring) check_size(r, key, 2.0 * g.ring->outer_radius);
    if (g.box) // a plane region's box spans all of z
      check_size(r, key, (g.box->hi - g.box->lo).head(p.sph().dimension).maxCoeff());
  }
}

void check_problem(Report& r, const ProblemSpec& p, bool front) {
  for (const auto& m : p.materials) check_material(r, m);
  check_sizes(r, p, front);
  check_loads(r, p);
  check_step(r, p);
  if (const StagedSpec* staged = std::get_if<StagedSpec>(&p.part))
    for (const auto& s : staged->stages) check_problem(r, s, false);
}

} // namespace

std::optional<UnitSystem> parse_units(const std::string& units) {
  static const std::map<std::string, double> forces{
      {"n", 1.0}, {"kn", 1e3}, {"mn", 1e6}, {"kgf", 9.80665}, {"lbf", 4.4482216152605}};
  static const std::map<std::string, double> lengths{{"m", 1.0},   {"mm", 1e-3}, {"cm", 1e-2},
                                                     {"um", 1e-6}, {"km", 1e3},  {"in", 0.0254}};
  static const std::map<std::string, double> times{
      {"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"ns", 1e-9}};
  static const std::map<std::string, double> masses{
      {"kg", 1.0}, {"g", 1e-3}, {"t", 1e3}, {"tonne", 1e3}};
  std::optional<double> force, length, time, mass;
  std::string token;
  std::istringstream in(lower(units));
  while (in >> token) {
    token.erase(std::remove(token.begin(), token.end(), ','), token.end());
    auto pick = [&](const std::map<std::string, double>& table, std::optional<double>& slot) {
      auto it = table.find(token);
      if (it == table.end() || slot) return false;
      slot = it->second;
      return true;
    };
    // "ms" is a time, never a mass; "t" a mass (tonne). Derived units (MPa, kgf/mm^2) are
    // implied by force and length and not read.
    pick(forces, force) || pick(lengths, length) || pick(times, time) || pick(masses, mass);
  }
  if (!force || !length) return std::nullopt;
  UnitSystem u;
  u.force = *force, u.length = *length;
  if (time)
    u.time = *time;
  else if (mass)
    u.time = std::sqrt(*mass * *length / *force);
  u.mass = mass ? *mass : u.force * u.time * u.time / u.length;
  return u;
}

std::vector<std::string> unit_sanity_warnings(const ProblemSpec& spec) {
  const std::optional<UnitSystem> u = parse_units(spec.units);
  if (!u) return {};
  Report r(*u, spec.units);
  const double consistent = u->force * u->time * u->time / u->length;
  if (std::abs(u->mass / consistent - 1.0) > 1e-6)
    r.add("units = '" + spec.units + "' is not a consistent set: force x time^2 / length is " +
          num(consistent) + " kg, the mass unit " + num(u->mass) +
          " kg; the solver assumes consistent units");
  check_problem(r, spec, true);
  return r.lines();
}

void warn_unit_sanity(const ProblemSpec& spec) {
  for (const auto& line : unit_sanity_warnings(spec)) log::warn(line);
}

} // namespace mf::spec
