// The Galerkin analyses of a problem file (elastic_static, elastoplastic_static and the 1D model
// problem): body, boundary conditions, load schedule and output (the discretisation:
// read_discretisation.cpp). Every key is checked; errors name the key path.
#include "meshfree/core/input_file.hpp"
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/galerkin_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>
#include <cmath>

namespace mf::spec {

namespace {

/// `stiffness_scale` = E / h: the penalty is alpha = penalty_scale * E / h unless an absolute
/// `penalty` is given ([Faraji 2007] uses alpha = 1e12 with E = 2e5 MPa).
BoundaryCondition read_condition(KeyReader& bc, double stiffness_scale) {
  BoundaryCondition c;
  c.key_path = bc.path();
  c.name = bc.text("name");
  check_name(bc, "name", c.name, false);
  c.on = read_region(bc, 2, kEdges | kBox);
  if (c.on.edges.empty() && !c.on.box)
    bc.error("edges", "name the boundary pieces ('edges') or give a 'box'");
  if (bc.has("displacement")) {
    c.constrains = true;
    YAML::Node n = bc.raw("displacement");
    if (n.IsScalar() && n.Scalar() == "exact") {
      c.value_from_exact = true;
      c.mask = Vec2(1.0, 1.0);
    } else {
      KeyReader u(n, bc.path_of("displacement"));
      if (u.has("x")) c.mask.x() = 1.0, c.value.x() = u.number("x");
      if (u.has("y")) c.mask.y() = 1.0, c.value.y() = u.number("y");
      u.allow("x");
      u.allow("y");
      if (u.has("exact") && (u.has("x") || u.has("y")))
        u.error("exact", "give either prescribed values (x, y) or 'exact', not both");
      if (u.has("exact")) {
        const std::string comps = u.choice("exact", {"x", "y", "xy"}, "xy");
        c.value_from_exact = true;
        c.mask = Vec2(comps.find('x') != std::string::npos, comps.find('y') != std::string::npos);
      }
      u.allow("exact");
      u.finish();
      if (c.mask.isZero())
        bc.error("displacement", "constrain at least one of x, y (or say 'exact')");
    }
    if (bc.has("penalty") && bc.has("penalty_scale"))
      bc.error("penalty_scale",
               "give either 'penalty' (absolute) or 'penalty_scale' (times E/h), not both");
    c.penalty = bc.has("penalty") ? bc.positive("penalty")
                                  : bc.positive("penalty_scale", 1e6) * stiffness_scale;
  }
  for (const char* key : {"penalty", "penalty_scale"}) {
    if (!c.constrains && bc.has(key)) bc.error(key, "a penalty needs a 'displacement' condition");
    bc.allow(key);
  }
  if (bc.has("traction")) {
    c.loads = true;
    YAML::Node n = bc.raw("traction");
    if (n.IsScalar() && n.Scalar() == "exact")
      c.traction_from_exact = true;
    else
      c.traction = bc.vec2("traction");
  }
  bc.allow("traction");
  if (bc.has("pressure")) {
    if (c.constrains || c.loads)
      bc.error("pressure", "give one of 'displacement', 'traction' or 'pressure'");
    c.loads = c.pressure_load = true;
    c.pressure = bc.number("pressure");
  }
  bc.allow("displacement");
  bc.allow("pressure");
  // A misspelt key ('tracton') is named before the condition is found to lack its kind.
  bc.finish();
  if (c.constrains == c.loads)
    bc.error("name", "a boundary condition needs exactly one of 'displacement', 'traction' or "
                     "'pressure'");
  return c;
}

std::optional<verification::ExactSolution> read_exact(KeyReader& r) {
  auto e = r.optional_map("exact");
  if (!e) return std::nullopt;
  const std::string kind = e->choice("solution", {"timoshenko_beam", "kirsch", "linear"}, "");
  verification::ExactSolution out;
  if (kind == "timoshenko_beam") {
    verification::TimoshenkoBeam b;
    b.P = e->number("P");
    b.L = e->positive("L");
    b.D = e->positive("D");
    out = b;
  } else if (kind == "kirsch") {
    verification::KirschPlate k;
    k.a = e->positive("radius");
    k.sigma0 = e->number("sigma0");
    out = k;
  } else {
    verification::LinearField f;
    f.u0 = e->vec2("u0");
    const std::vector<Vec2> g = e->vec2_list("gradient");
    if (g.size() != 2) e->error("gradient", "expected [[dux/dx, dux/dy], [duy/dx, duy/dy]]");
    f.G << g[0].x(), g[0].y(), g[1].x(), g[1].y();
    out = f;
  }
  e->finish();
  return out;
}

/// steps: [{name, increments, load_factor, factors: {condition: target}}]; see LoadStep. With a
/// geostatic initial stress the schedule starts with the step "geostatic": one increment with
/// the body force at its full value and every condition at 0, the equilibrium iteration of the
/// initial stress; `load_factor` then moves the conditions only (the body force stays on unless
/// `factors` names it).
} // namespace

std::vector<LoadStep> read_steps(KeyReader& r, const std::vector<std::string>& boundary,
                                 bool geostatic) {
  std::vector<LoadStep> steps;
  const std::size_t n = boundary.size() + 1; // the body force is the last factor
  std::vector<double> current(n, 0.0);
  if (geostatic) {
    LoadStep g;
    g.name = "geostatic";
    g.target = current;
    g.target.back() = 1.0;
    current = g.target;
    steps.push_back(g);
  }
  std::vector<KeyReader> list = r.map_list("steps");
  if (list.empty() && !geostatic)
    r.error("steps", "an elastoplastic analysis needs a load schedule: a list of "
                     "{name, load_factor, increments}");
  for (KeyReader& k : list) {
    LoadStep s;
    s.name = k.text("name");
    check_name(k, "name", s.name, false);
    for (const auto& other : steps)
      if (other.name == s.name) k.error("name", "another step is named '" + s.name + "'");
    s.increments = k.integer("increments", 1, 1, 1000000);
    std::vector<char> named(n, 0);
    s.target = current;
    if (auto f = k.optional_map("factors")) {
      for (std::size_t c = 0; c < n; ++c) {
        const std::string key = c < boundary.size() ? boundary[c] : "body_force";
        if (f->has(key)) {
          s.target[c] = f->number(key);
          named[c] = 1;
        }
      }
      try {
        f->finish();
      } catch (const Error& e) {
        fail(e.what(), " (factors name boundary conditions or 'body_force')");
      }
    }
    if (k.has("load_factor")) {
      const double lf = k.number("load_factor");
      for (std::size_t c = 0; c < n; ++c)
        if (!named[c] && !(geostatic && c + 1 == n)) s.target[c] = lf;
    } else if (!k.has("factors")) {
      k.error("load_factor", "give the step's target 'load_factor' or 'factors'");
    }
    k.allow("load_factor");
    k.finish();
    current = s.target;
    steps.push_back(s);
  }
  return steps;
}

NonlinearSpec read_nonlinear(KeyReader& r) {
  NonlinearSpec s;
  if (auto n = r.optional_map("nonlinear")) {
    s.tolerance = n->positive("tolerance", s.tolerance);
    if (s.tolerance >= 1e-2)
      n->error("tolerance", "a relative residual tolerance below 1e-2 is needed, got " +
                                detail::concat(s.tolerance));
    s.max_iterations = n->integer("max_iterations", s.max_iterations, 1, 200);
    s.max_cutbacks = n->integer("max_cutbacks", s.max_cutbacks, 0, 30);
    s.keep_tangent = n->number("keep_tangent", s.keep_tangent);
    if (!(s.keep_tangent >= 0.0 && s.keep_tangent < 1.0))
      n->error("keep_tangent", "expected a contraction from 0 (a new tangent every iteration) "
                               "up to but not including 1, got " +
                                   detail::concat(s.keep_tangent));
    n->finish();
  }
  return s;
}

void parse_model_1d(KeyReader& r, ProblemSpec& p, const std::string& base_dir) {
  ModelProblem1D& model = p.part.emplace<ModelProblem1D>();
  KeyReader m = r.map("problem_1d");
  model.length = m.positive("length");
  model.sine_amplitude = m.number("sine_amplitude", 1.0);
  model.sine_waves = m.positive("sine_waves", 1.0);
  model.linear = m.number("linear", 0.0);
  m.finish();
  const BoundingBox line{{0.0, 0.0}, {model.length, 0.0}};
  model.discretisation = read_discretisation(r, 1, line, base_dir);
  model.penalty = r.positive("penalty", 1e6 / model.discretisation.spacing);
}

/// The material of a Galerkin analysis: the one `material:` names, or the single entry; it
/// needs E and nu, and plasticity exactly when the analysis is elastoplastic.
int take_material(KeyReader& r, const ProblemSpec& p, const std::string& analysis) {
  int index = 0;
  if (r.has("material")) {
    index = find_material(r, "material", p.materials, r.text("material"));
  } else if (p.materials.size() != 1) {
    r.error("material", "name the material of the body (the file lists " +
                            std::to_string(p.materials.size()) + " materials)");
  }
  r.allow("material");
  const MaterialSpec& m = p.materials[index];
  if (!(m.E > 0.0)) material_error(m, "E", "analysis " + analysis + " needs Young's modulus E");
  if (!m.has_nu)
    material_error(m, "nu",
                   "analysis " + analysis +
                       " needs Poisson's ratio nu (or the shear "
                       "modulus)");
  return index;
}

namespace {

/// A material a Galerkin body uses: it needs E and nu, and plasticity only in an elastoplastic
/// analysis.
void check_body_material(const MaterialSpec& m, const std::string& analysis, bool plastic) {
  if (!(m.E > 0.0)) material_error(m, "E", "analysis " + analysis + " needs Young's modulus E");
  if (!m.has_nu)
    material_error(m, "nu",
                   "analysis " + analysis + " needs Poisson's ratio nu (or the shear modulus)");
  if (!plastic && m.plasticity)
    material_error(m, "plasticity", "used only by analysis elastoplastic_static");
}

/// material_regions: [{material, box | circle | ring | holes}], later entries winning.
void read_material_regions(KeyReader& r, ProblemSpec& p, const std::string& analysis,
                           bool plastic) {
  for (KeyReader& g : r.map_list("material_regions")) {
    MaterialRegion mr;
    mr.key_path = g.path();
    mr.material = find_material(g, "material", p.materials, g.text("material"));
    mr.region = read_region(g, 2, kSolids);
    if (mr.region.everything())
      g.error("material", "give the region of the material: a box, circle, ring or holes");
    g.finish();
    check_body_material(p.materials[mr.material], analysis, plastic);
    p.galerkin().material_regions.push_back(mr);
  }
}

/// parts: [{group, material}]: each group of the geometry file's surfaces made of its material (a
/// material region whose region is the group's body, before `material_regions`, which win over
/// it); every group of the file needs one, and each is named once. The body's `material`, where
/// not given, is the first part's.
void read_parts(KeyReader& r, ProblemSpec& p, const std::string& analysis, bool plastic) {
  auto& galerkin = p.galerkin();
  for (const PartMaterial& part : read_part_materials(r, p)) {
    MaterialRegion mr;
    mr.key_path = part.key_path;
    mr.material = part.material;
    mr.region.part = part.part->body;
    check_body_material(p.materials[mr.material], analysis, plastic);
    galerkin.material_regions.push_back(std::move(mr));
  }
  if (galerkin.material_index < 0 && !galerkin.material_regions.empty())
    galerkin.material_index = galerkin.material_regions[0].material;
}

/// gravity: [gx, gy] (an acceleration; every material of the body needs its density) and
/// initial_stress: {type: geostatic, surface, k0}.
void read_gravity_and_initial_stress(KeyReader& r, ProblemSpec& p, bool plastic) {
  auto& galerkin = p.galerkin();
  if (r.has("gravity")) {
    galerkin.gravity = r.vec2("gravity");
    std::vector<int> used{galerkin.material_index};
    for (const MaterialRegion& mr : galerkin.material_regions) used.push_back(mr.material);
    for (int k : used)
      if (!(p.materials[k].density > 0.0))
        material_error(p.materials[k], "density",
                       "gravity needs the density of every material of the body");
  }
  auto s = r.optional_map("initial_stress");
  if (!s) return;
  if (!plastic)
    r.error("initial_stress",
            "used only by analysis elastoplastic_static (its first step is the equilibrium "
            "iteration)");
  s->choice("type", {"geostatic"}, "");
  if (galerkin.gravity.isZero())
    r.error("initial_stress", "a geostatic initial stress needs 'gravity' (the weight of the "
                              "column above each point)");
  if (galerkin.gravity.x() != 0.0 || !(galerkin.gravity.y() < 0.0))
    r.error("gravity", "a geostatic initial stress needs gravity along -y, [0, -g] (the column "
                       "above each point lies towards +y)");
  GeostaticStress g;
  g.surface = s->number("surface");
  g.k0 = s->number("k0");
  if (!(g.k0 >= 0.0)) s->error("k0", "expected a number >= 0, got " + detail::concat(g.k0));
  s->finish();
  galerkin.initial_stress = g;
}

/// The boundary conditions: unique names, 'exact' only with an exact solution, selectors that
/// pick something, and at least one displacement condition.
void read_boundary(KeyReader& r, ProblemSpec& p) {
  auto& galerkin = p.galerkin();
  // Default penalty: alpha = 1e6 E / h, stiff enough that the constraint error is ~1e-6 of the
  // boundary displacement scale, and far from the round-off limit of a direct solve.
  const double stiffness_scale = p.elasticity().E / galerkin.discretisation.spacing;
  for (KeyReader& bc : r.map_list("boundary")) {
    galerkin.boundary.push_back(read_condition(bc, stiffness_scale));
    const BoundaryCondition& c = galerkin.boundary.back();
    for (std::size_t k = 0; k + 1 < galerkin.boundary.size(); ++k)
      if (galerkin.boundary[k].name == c.name)
        bc.error("name",
                 "'" + c.name + "' is used by " + galerkin.boundary[k].key_path + " already");
    if ((c.value_from_exact || c.traction_from_exact) && !galerkin.exact)
      bc.error(c.constrains ? "displacement" : "traction",
               "'exact' needs an 'exact' section in the problem");
    select_boundary(p.domain, c.on, c.key_path); // rejects selectors that pick nothing
  }
  if (galerkin.boundary.empty()) r.error("boundary", "at least one boundary condition is required");
  bool constrained = false;
  for (const auto& c : galerkin.boundary) constrained = constrained || c.constrains;
  if (!constrained)
    r.error("boundary", "no displacement condition: the body is free to move as a rigid body");
}

/// The plasticity law, the load steps and the Newton controls belong to elastoplastic_static.
void read_plastic_controls(KeyReader& r, ProblemSpec& p, bool plastic) {
  auto& galerkin = p.galerkin();
  const MaterialSpec& mat = p.materials[galerkin.material_index];
  // A material without plasticity is elastic at its points. An elastoplastic analysis of one
  // elastic material and nothing else is an elastic_static problem; with material regions,
  // gravity or an initial stress, or as the preload stage of a staged run, it is an elastic
  // preload.
  const bool preload = !galerkin.material_regions.empty() || !galerkin.gravity.isZero() ||
                       galerkin.initial_stress || !p.stage.empty();
  if (plastic && !p.plasticity() && !preload)
    material_error(mat, "plasticity", "analysis elastoplastic_static needs a plasticity law");
  if (!plastic && p.plasticity())
    material_error(mat, "plasticity", "used only by analysis elastoplastic_static");
  if (plastic) {
    std::vector<std::string> names;
    for (const BoundaryCondition& c : galerkin.boundary) names.push_back(c.name);
    galerkin.steps = read_steps(r, names, galerkin.initial_stress.has_value());
    galerkin.nonlinear = read_nonlinear(r);
  } else {
    for (const char* key : {"steps", "nonlinear"})
      if (r.has(key)) r.error(key, "used only by analysis elastoplastic_static");
  }
}

/// output.gauges: points of the body whose displacement a run records (history.csv).
void read_body_gauges(KeyReader& out, ProblemSpec& p) {
  auto& galerkin = p.galerkin();
  galerkin.gauges = read_gauges(out, 2);
  for (std::size_t k = 0; k < galerkin.gauges.size(); ++k) {
    const Vec2 at = galerkin.gauges[k].at.head<2>();
    if (!p.domain.contains(at, 1e-9 * p.domain.bounds().size().maxCoeff()))
      fail(out.path_of("gauges"), "[", k, "].at: the point (", detail::concat(at.x(), ", ", at.y()),
           ") is not in the body");
  }
}

void read_checkpoint_output(KeyReader& out, ProblemSpec& p, bool plastic) {
  auto& galerkin = p.galerkin();
  for (const char* key : {"checkpoint_every", "checkpoint_wall_interval"})
    if (!plastic && out.has(key))
      out.error(key, "checkpoints are written only by analysis elastoplastic_static");
  galerkin.checkpoint.interval = out.integer("checkpoint_every", 0, 0, 1000000);
  galerkin.checkpoint.wall_interval = out.number("checkpoint_wall_interval", 600.0);
  if (!(galerkin.checkpoint.wall_interval >= 0.0) ||
      !std::isfinite(galerkin.checkpoint.wall_interval))
    out.error("checkpoint_wall_interval", "expected seconds of wall time, 0 for none, got " +
                                              detail::concat(galerkin.checkpoint.wall_interval));
  const auto& adapt = galerkin.discretisation.adapt;
  for (const char* key : {"checkpoint_every", "checkpoint_wall_interval"})
    if (adapt && adapt->every > 0 && out.has(key) && out.number(key, 0.0) != 0.0)
      out.error(key, "a run whose cloud is refined during the analysis "
                     "(discretisation.adapt.every) writes no checkpoints: 0 or leave it out");
}

/// One output.lines entry: a sampled segment with at least one sample point in the body.
LineSpec read_line(KeyReader& l, const ProblemSpec& p) {
  LineSpec s;
  s.name = l.text("name");
  s.from = l.vec2("from");
  s.to = l.vec2("to");
  s.points = l.integer("points", 51, 2, 1000000);
  check_name(l, "name", s.name, false);
  for (const auto& other : p.galerkin().lines)
    if (other.name == s.name) l.error("name", "another line is named '" + s.name + "'");
  bool inside = false;
  for (int k = 0; k < s.points && !inside; ++k)
    inside = p.domain.contains(s.from + (s.to - s.from) * (static_cast<double>(k) / (s.points - 1)),
                               1e-9);
  if (!inside) l.error("from", "no sample point of the line lies in the body");
  l.finish();
  return s;
}

void read_output(KeyReader& r, ProblemSpec& p, bool plastic) {
  auto& galerkin = p.galerkin();
  if (auto out = r.optional_map("output")) {
    read_body_gauges(*out, p);
    galerkin.fields_every = out->integer("fields_every", 1, 1, 1000000);
    read_checkpoint_output(*out, p, plastic);
    for (KeyReader& l : out->map_list("lines")) galerkin.lines.push_back(read_line(l, p));
    out->finish();
  }
}

} // namespace

void parse_galerkin(KeyReader& r, ProblemSpec& p, const std::string& base_dir) {
  auto& galerkin = p.galerkin();
  const bool plastic = p.analysis == Analysis::ElastoplasticStatic;
  const std::string analysis = plastic ? "elastoplastic_static" : "elastic_static";
  if (p.model_type != ModelType::PlaneStress && p.model_type != ModelType::PlaneStrain)
    r.error("model", "analysis " + analysis + " takes model.type plane_stress or plane_strain");
  // With parts, the body's material may be left to them (read_parts).
  galerkin.material_index =
      r.has("parts") && !r.has("material") ? -1 : take_material(r, p, analysis);
  galerkin.linear_solver = read_linear_solver(r);
  galerkin.discretisation =
      read_discretisation(r, 2, p.domain.bounds(), base_dir, galerkin.linear_solver);
  if (galerkin.discretisation.cell_mean_volumetric && p.model_type == ModelType::PlaneStress)
    r.error("discretisation.quadrature.volumetric_strain",
            "cell_mean is for plane_strain and solid_3d bodies: a plane-stress body's thickness "
            "changes with its volume freely, so nothing locks");
  const auto& adapt = galerkin.discretisation.adapt;
  if (!plastic && adapt && adapt->every > 0)
    r.error("discretisation.adapt.every",
            "refines between the increments of elastoplastic_static; an elastic_static solve "
            "has none (leave 'every' out: pilot solves refine its cloud)");
  galerkin.exact = read_exact(r);
  if (r.has("body_force")) galerkin.body_force = r.vec2("body_force");
  r.allow("body_force");
  read_parts(r, p, analysis, plastic);
  read_material_regions(r, p, analysis, plastic);
  read_gravity_and_initial_stress(r, p, plastic);
  read_boundary(r, p);
  read_plastic_controls(r, p, plastic);
  read_output(r, p, plastic);
  // A checkpoint holds the state on one cloud; a run that changes its cloud writes none.
  if (adapt && adapt->every > 0) galerkin.checkpoint = CheckpointPolicy{0.0, 0.0};
}

} // namespace mf::spec
