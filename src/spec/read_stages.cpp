// analysis: staged. Each stage is read as a one-analysis problem made of the keys shared at the
// top of the file (name, description, units, model, materials, geometry) and its own keys; a
// later stage names the stage it starts from, which of that stage's conditions it holds and
// which it releases, and how the transferred state is settled. Everything a transfer cannot take
// is refused here, before anything runs.
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>
#include <cmath>

namespace mf::spec {

namespace {

const char* const kSharedKeys[] = {"name",  "description", "units",
                                   "model", "materials",   "geometry"};
const char* const kLinkKeys[] = {"name", "from", "hold", "release", "mirror", "settle", "transfer"};

bool is_link_key(const std::string& key) {
  return std::find(std::begin(kLinkKeys), std::end(kLinkKeys), key) != std::end(kLinkKeys);
}

/// The problem file of one stage: the shared keys and the stage's own (link keys left out).
YAML::Node stage_file(KeyReader& top, KeyReader& s) {
  YAML::Node merged(YAML::NodeType::Map);
  // SPH builds its bodies from its own regions, not from the geometry.
  const bool sph =
      s.has("analysis") && s.raw("analysis").IsScalar() && s.raw("analysis").Scalar() == "sph";
  for (const char* key : kSharedKeys)
    if (top.has(key) && !(sph && std::string(key) == "geometry"))
      merged[key] = YAML::Clone(top.raw(key));
  for (const auto& kv : s.raw_map()) {
    const std::string key = kv.first.Scalar();
    if (is_link_key(key)) continue;
    if (merged[key].IsDefined() && !merged[key].IsNull())
      s.error(key, "given at the top of the file already");
    merged[key] = YAML::Clone(kv.second);
  }
  return merged;
}

/// Reads a stage's problem; an error in a shared key given at the top of the file keeps its
/// top-level path, any other (a key of the stage's own, or one it lacks) is given the stage's
/// path (stages[k].key...).
ProblemSpec parse_stage(YAML::Node file, KeyReader& top, const std::string& path,
                        const std::string& name, const std::string& base_dir) {
  try {
    return parse_problem(file, base_dir, name);
  } catch (const Error& e) {
    const std::string what = e.what();
    const std::size_t end = what.find_first_of(".[:");
    const std::string first = what.substr(0, end);
    const bool shared =
        std::find(std::begin(kSharedKeys), std::end(kSharedKeys), first) != std::end(kSharedKeys);
    if (end == std::string::npos || (shared && top.has(first))) throw;
    throw Error(path + "." + what);
  }
}

std::vector<std::string> names(KeyReader& r, const std::string& key) {
  std::vector<std::string> out;
  if (!r.has(key)) return out;
  const YAML::Node list = r.raw(key);
  if (!list.IsSequence()) r.error(key, "expected a list of condition names");
  for (const auto& n : list) {
    if (!n.IsScalar()) r.error(key, "expected a list of condition names");
    const std::string name = n.Scalar();
    if (std::find(out.begin(), out.end(), name) != out.end())
      r.error(key, "lists '" + name + "' twice");
    out.push_back(name);
  }
  return out;
}

bool explicit_dynamics(Analysis a) {
  return a == Analysis::Sph || a == Analysis::Peridynamics;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

/// The materials a Galerkin stage uses: its own and those of its material regions.
std::vector<int> materials_used(const ProblemSpec& p) {
  if (p.is_solid()) return {p.solid().material_index};
  auto& galerkin = p.galerkin();
  std::vector<int> used{galerkin.material_index};
  for (const MaterialRegion& r : galerkin.material_regions) used.push_back(r.material);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  return used;
}

/// A 3D preload's displacement conditions are held on all three components (a clamp) or on one
/// (a roller): a particle layer holds no other combination.
void check_solid_holds(KeyReader& s, const StageLink& l, const ProblemSpec& from) {
  if (!from.is_solid()) return;
  for (const FaceCondition& bc : from.solid().boundary) {
    const int held = static_cast<int>(bc.mask.sum());
    if (!bc.constrains || held == 1 || held == 3 ||
        std::find(l.hold.begin(), l.hold.end(), bc.name) == l.hold.end())
      continue;
    s.error("hold", "'" + bc.name + "' holds " + std::to_string(held) +
                        " of the 3 displacement components; a held condition holds all three (a "
                        "clamp) or one (a roller): release it, or split it into rollers");
  }
}

/// What the next stage can take from a preload, checked against the next stage's analysis.
void check_transfer(const ProblemSpec& from, const ProblemSpec& to) {
  // A plane-stress preload cannot reach an SPH stage: the SPH stage's own reading of the shared
  // model refuses plane stress (2D SPH is plane strain), naming model.type.
  if (to.analysis != Analysis::Peridynamics) return;
  const bool state_based = to.pd().state_based();
  // Bond-based peridynamics has a fixed Poisson ratio (Silling 2000): 1/3 in plane stress, 1/4
  // in plane strain and 3D. The state-based LPS takes the preload's own.
  const double nu_pd = to.model_type == ModelType::PlaneStress ? 1.0 / 3.0 : 0.25;
  for (int m : materials_used(from)) {
    const MaterialSpec& mat = from.materials[m];
    const std::string& path = mat.key_path;
    if (mat.plasticity)
      throw Error(path + ".plasticity: a plastic preload (plastic strain, hardening) cannot start "
                         "a peridynamic stage, whose bonds carry no plastic state");
    if (!state_based && std::abs(mat.nu - nu_pd) > 0.02)
      throw Error(path + ".nu: bond-based peridynamics in " +
                  (to.model_type == ModelType::PlaneStress ? "plane stress" : "this model") +
                  " has Poisson's ratio " + detail::concat(nu_pd) + "; the preload's " +
                  detail::concat(mat.nu) + " differs by more than 0.02");
  }
}

/// What the explicit stage can take: SPH holds gravity but no uniform body force; the implicit
/// peridynamic equilibrium solves plane bodies (a 3D body relaxes by ADR, its default there).
void check_explicit_stage(KeyReader& s, const StageLink& l, const ProblemSpec& from,
                          const ProblemSpec& to) {
  if (to.analysis == Analysis::Sph &&
      std::find(l.hold.begin(), l.hold.end(), "body_force") != l.hold.end())
    s.error("hold", std::string("SPH holds gravity, not a uniform body force: release "
                                "'body_force'") +
                        (from.is_solid() ? "" : " (or give the preload 'gravity')"));
  if (to.analysis == Analysis::Peridynamics && to.model_type == ModelType::Solid3D &&
      l.implicit_equilibrium && l.equilibrium_given)
    s.error("transfer", "equilibrium: newton solves plane peridynamic bodies; a 3D body relaxes "
                        "to its equilibrium by adr");
}

StageLink read_link(KeyReader& s, const std::vector<ProblemSpec>& earlier, int k) {
  StageLink l;
  l.key_path = s.path();
  if (!s.has("from")) {
    if (k > 0) s.error("from", "a later stage names the stage it starts from");
    return l;
  }
  const std::string from = s.text("from");
  for (std::size_t j = 0; j < earlier.size(); ++j)
    if (earlier[j].stage == from) l.from = static_cast<int>(j);
  if (l.from < 0) {
    std::vector<std::string> known;
    for (const auto& e : earlier) known.push_back(e.stage);
    s.error("from", "unknown stage '" + from + "' (earlier stages: " + joined(known) + ")");
  }
  l.hold = names(s, "hold");
  l.release = names(s, "release");
  if (auto m = s.optional_map("settle")) {
    l.settle_time = m->positive("time");
    l.settle_damping = m->positive("damping");
    m->finish();
  }
  if (auto t = s.optional_map("transfer")) {
    l.return_to_surface =
        t->choice("outside_yield_surface", {"report", "return"}, "report") == "return";
    l.equilibrium_given = t->has("equilibrium");
    l.implicit_equilibrium = t->choice("equilibrium", {"newton", "adr"}, "newton") == "newton";
    l.relax_tolerance = t->positive("relax_tolerance", l.relax_tolerance);
    l.relax_max_iterations =
        t->integer("relax_max_iterations", l.relax_max_iterations, 1, 100000000);
    t->allow("relax_from_zero");
    if (t->has("relax_from_zero")) l.relax_from_zero = t->raw("relax_from_zero").as<bool>();
    t->finish();
  }
  for (KeyReader& m : s.map_list("mirror")) {
    MirrorPlane plane;
    plane.axis = m.choice("axis", {"x", "y", "z"}, "")[0] - 'x';
    plane.at = m.number("at", 0.0);
    m.finish();
    l.mirror.push_back(plane);
  }
  return l;
}

/// Every condition of the preload is held or released, and nothing else is named.
void check_conditions(KeyReader& s, const StageLink& l, const ProblemSpec& from) {
  const std::vector<std::string> known = stage_conditions(from);
  for (const char* key : {"hold", "release"})
    for (const auto& n : key[0] == 'h' ? l.hold : l.release)
      if (std::find(known.begin(), known.end(), n) == known.end())
        s.error(key, "stage '" + from.stage + "' has no condition '" + n +
                         "' (its conditions: " + joined(known) + ")");
  for (const auto& n : l.hold)
    if (std::find(l.release.begin(), l.release.end(), n) != l.release.end())
      s.error("release", "'" + n + "' is held and released");
  for (const auto& n : known)
    if (std::find(l.hold.begin(), l.hold.end(), n) == l.hold.end() &&
        std::find(l.release.begin(), l.release.end(), n) == l.release.end())
      s.error("hold", "the condition '" + n + "' of stage '" + from.stage +
                          "' is neither held nor released (hold: [...] keeps it on, release: "
                          "[...] takes it off)");
}

} // namespace

std::vector<std::string> stage_conditions(const ProblemSpec& p) {
  std::vector<std::string> out;
  if (p.is_solid()) {
    for (const auto& bc : p.solid().boundary) out.push_back(bc.name);
    if (p.solid().body_force.norm() > 0.0) out.push_back("body_force");
    return out;
  }
  auto& galerkin = p.galerkin();
  for (const auto& bc : galerkin.boundary) out.push_back(bc.name);
  if (galerkin.body_force.norm() > 0.0) out.push_back("body_force");
  if (galerkin.gravity.norm() > 0.0) out.push_back("gravity");
  return out;
}

void parse_stages(KeyReader& r, ProblemSpec& p, const std::string& base_dir) {
  std::vector<KeyReader> list = r.map_list("stages");
  if (list.empty()) r.error("stages", "expected a list of stages {name, analysis, ...}");
  // What runs: one stage as its analysis, or a preload and one explicit stage starting from it.
  if (list.size() > 2)
    r.error("stages", "a staged run is a preload followed by one explicit stage that starts from "
                      "it (the file lists " +
                          std::to_string(list.size()) + " stages)");
  for (std::size_t k = 0; k < list.size(); ++k) {
    KeyReader& s = list[k];
    const std::string name = s.text("name");
    check_name(s, "name", name);
    for (const auto& e : p.staged().stages)
      if (e.stage == name) s.error("name", "another stage is named '" + name + "'");
    // The link first: where a stage starts from is checked before its own keys.
    const YAML::Node own = s.raw_map();
    KeyReader link_reader(own, s.path());
    for (const auto& kv : own)
      if (!is_link_key(kv.first.Scalar())) link_reader.allow(kv.first.Scalar());
    link_reader.allow("name");
    StageLink link = read_link(link_reader, p.staged().stages, static_cast<int>(k));
    link_reader.finish();
    ProblemSpec stage = parse_stage(stage_file(r, s), r, s.path(), name, base_dir);
    // The bounds on an explicit stage's run (time.end, output intervals) are checked on its set-up,
    // after reading: they name the stage's keys by its path.
    if (stage.is_galerkin() && stage.galerkin().discretisation.adapt)
      s.error("discretisation.adapt", "a stage's cloud is not adapted; adapt it in a run of its "
                                      "own and give the stage that run's refinement boxes");
    if (stage.is_pd()) stage.pd().key_prefix = s.path() + ".";
    if (stage.is_sph()) stage.sph().key_prefix = s.path() + ".";
    if (link.from >= 0) {
      const ProblemSpec& from = p.staged().stages[link.from];
      if (from.analysis != Analysis::ElastoplasticStatic || !explicit_dynamics(stage.analysis))
        s.error("from", "a stage starts from an implicit preload (elastoplastic_static; an "
                        "elastic preload is one whose materials have no plasticity) and is an "
                        "explicit analysis (sph or peridynamics)");
      check_conditions(link_reader, link, from);
      check_solid_holds(link_reader, link, from);
      check_transfer(from, stage);
      check_explicit_stage(link_reader, link, from, stage);
      if (stage.is_pd() && stage.pd().state_plastic()) {
        if (link.implicit_equilibrium && link.equilibrium_given)
          link_reader.error("transfer", "equilibrium: newton solves elastic bodies; a body of "
                                        "law: eps relaxes to its equilibrium by adr");
        link.implicit_equilibrium = false; // ADR
      }
      if (stage.analysis == Analysis::Peridynamics && stage.model_type == ModelType::Solid3D)
        link.implicit_equilibrium = false; // ADR, the 3D default
      if (stage.analysis == Analysis::Peridynamics && link.settle_time > 0.0)
        link_reader.error("settle", "a peridynamic stage starts from its own static equilibrium "
                                    "under the held conditions (transfer.relax_tolerance); "
                                    "settle is for SPH stages");
    }
    p.staged().stages.push_back(std::move(stage));
    p.staged().links.push_back(std::move(link));
  }
  for (const char* key : kSharedKeys) r.allow(key);
  r.allow("analysis");
}

} // namespace mf::spec
