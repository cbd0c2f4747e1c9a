// The discretisation of a Galerkin body in a problem file (plane, solid or the 1D model
// problem): the method (meshfree or finite elements), node spacing and refinement boxes, shape
// functions, quadrature and the linear solver. Every key is checked; errors name the key path.
#include "meshfree/core/input_file.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/spec/analysis_read.hpp"
#include "meshfree/spec/galerkin_read.hpp"
#include "meshfree/spec/spec_read.hpp"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace mf::spec {

namespace {

kernels::WindowType window_type(const std::string& s) {
  if (s == "cubic_spline") return kernels::WindowType::CubicSpline;
  if (s == "quartic_spline") return kernels::WindowType::QuarticSpline;
  return kernels::WindowType::Gaussian;
}

} // namespace

LinearSolverSpec read_linear_solver(KeyReader& r) {
  LinearSolverSpec s;
  if (auto l = r.optional_map("linear_solver")) {
    const std::string type = l->choice("type", {"auto", "direct", "multigrid"}, "auto");
    s.type = type == "direct"      ? LinearSolverSpec::Type::Direct
             : type == "multigrid" ? LinearSolverSpec::Type::Multigrid
                                   : LinearSolverSpec::Type::Auto;
    s.multigrid_above = l->positive("multigrid_above", s.multigrid_above);
    l->finish();
  }
  return s;
}

double bytes_per_node(const LinearSolverSpec& solver, double count) {
  return solver.multigrid_for(2.0 * count) ? bytes_per::galerkin_node_multigrid
                                           : bytes_per::galerkin_node;
}

namespace {

/// discretisation.fem: the element (in 3D also tetrahedra), an optional gmsh mesh file and the
/// quadrature order.
void read_fem_options(KeyReader& d, int dim, const std::string& base_dir, DiscretisationSpec& s) {
  if (auto f = d.optional_map("fem")) {
    // In 3D, q4 and q8 name the plane elements extruded into 8- and 20-node bricks (hex8, hex20).
    s.fem.element =
        dim == 3
            ? f->choice("element", {"hex8", "hex20", "tet4", "tet10", "q4", "q8", "t3"}, "hex20")
            : f->choice("element", {"t3", "q4", "q8"}, "q8");
    if (f->has("mesh")) {
      const std::string mesh = f->text("mesh");
      s.fem.mesh = !mesh.empty() && mesh.front() == '/' ? mesh : base_dir + mesh;
      if (std::filesystem::exists(s.fem.mesh)) try {
          require_regular_file(s.fem.mesh, "mesh file");
        } catch (const Error& e) {
          f->error("mesh", e.what());
        }
      std::ifstream probe(s.fem.mesh);
      if (!probe.good())
        f->error("mesh", "cannot open the mesh file '" + one_line(s.fem.mesh) + "'");
    }
    f->allow("mesh");
    s.fem.order = f->integer("order", 0, 1, 10);
    f->finish();
  }
}

/// The spacing, refused beyond the body's size; returns the estimated node count over the body.
double read_spacing(KeyReader& d, const BoundingBox& bounds, const LinearSolverSpec& solver,
                    DiscretisationSpec& s) {
  s.spacing = d.positive("spacing");
  // Node counts estimated in floating point, so that a tiny spacing cannot overflow a count.
  const Vec2 size = bounds.hi - bounds.lo;
  // A spacing beyond the body leaves a lattice of its corners, whose supports (dilation times the
  // spacing) dwarf it: the shape functions fail in the run (at 1e6 on a unit plate), so the
  // input is refused here, where `check` sees it too.
  if (s.spacing > size.maxCoeff())
    d.error("spacing", detail::concat("expected at most the body's size (", size.x(), " x ",
                                      size.y(), "), got ", s.spacing));
  const double nodes = (size.x() / s.spacing + 1.0) * (size.y() / s.spacing + 1.0);
  require_memory(d.path_of("spacing"), "nodes over the body", nodes, bytes_per_node(solver, nodes));
  return nodes;
}

/// The corners' count of numbers: 3 where a solid's box gives z, else 2.
int box_dimension(KeyReader& f, int dim) {
  const YAML::Node b = f.raw("box");
  return dim == 3 && b.IsSequence() && b.size() > 0 && b[0].IsSequence() && b[0].size() == 3 ? 3
                                                                                             : 2;
}

/// One discretisation.refinement box, clipped to the body's section (a solid's range along z is
/// checked against its depth by the solid's reader); adds its node count in the section to
/// `nodes_total`.
geometry::Refinement read_refinement(KeyReader& f, int dim, const BoundingBox& bounds,
                                     const LinearSolverSpec& solver, const DiscretisationSpec& s,
                                     double& nodes_total) {
  geometry::Refinement ref;
  ref.along_z = box_dimension(f, dim) == 3;
  const Box b = read_box(f, "box", ref.along_z ? 3 : 2);
  ref.box = BoundingBox{b.lo.head<2>(), b.hi.head<2>()};
  ref.z_lo = b.lo.z();
  ref.z_hi = b.hi.z();
  ref.spacing = f.positive("spacing");
  if (ref.spacing >= s.spacing)
    f.error("spacing", "a refinement must be finer than discretisation.spacing");
  const Vec2 lo = ref.box.lo.cwiseMax(bounds.lo), hi = ref.box.hi.cwiseMin(bounds.hi);
  const Vec2 extent = (hi - lo).cwiseMax(Vec2::Zero());
  // The box is clipped to the body's bounds and one spacing around them: what lies farther
  // out refines nothing, and node generation walks the whole box.
  const Vec2 margin(s.spacing, s.spacing);
  const Vec2 clip_lo = ref.box.lo.cwiseMax(bounds.lo - margin);
  const Vec2 clip_hi = ref.box.hi.cwiseMin(bounds.hi + margin);
  if (!(clip_lo.array() < clip_hi.array()).all())
    f.error("box", "lies outside the body: it refines nothing");
  ref.box = BoundingBox{clip_lo, clip_hi};
  const double nodes = (extent.x() / ref.spacing + 1.0) * (extent.y() / ref.spacing + 1.0);
  require_memory(f.path_of("spacing"), "nodes in the box", nodes, bytes_per_node(solver, nodes));
  nodes_total += nodes;
  f.finish();
  return ref;
}

/// The shape functions: approximation, basis, window, support shape and dilation.
void read_shape_functions(KeyReader& d, int dim, DiscretisationSpec& s) {
  const std::string approx = d.choice("approximation", {"rk", "mls"}, "rk");
  s.shape.approximation = approx == "rk" ? kernels::Approximation::ReproducingKernel
                                         : kernels::Approximation::MovingLeastSquares;
  s.shape.basis = d.choice("basis", {"linear", "quadratic"}, "linear") == "linear"
                      ? kernels::Basis::Linear
                      : kernels::Basis::Quadratic;
  s.shape.window.type = window_type(
      d.choice("window", {"cubic_spline", "quartic_spline", "gaussian"}, "cubic_spline"));
  s.shape.window.gaussian_shape = d.positive("gaussian_shape", 0.4);
  s.shape.support = d.choice("support", {"circular", "rectangular"}, "circular") == "circular"
                        ? kernels::SupportShape::Circular
                        : kernels::SupportShape::Rectangular;
  s.shape.dim = dim;
  const double default_dilation = s.shape.basis == kernels::Basis::Quadratic ? 3.0 : 2.0;
  s.dilation = d.scalar_or_vec2("dilation", Vec2(default_dilation, default_dilation));
  const double min_dilation = s.shape.basis == kernels::Basis::Quadratic ? 2.0 : 1.0;
  if (s.dilation.minCoeff() <= min_dilation)
    d.error("dilation", "must exceed " + std::to_string(min_dilation) +
                            " so that every point is covered by enough nodes for the basis");
  s.visibility = d.choice("visibility", {"false", "true"}, "false") == "true";
  if (s.visibility && dim != 2)
    d.error("visibility", "hides nodes behind a plane body's holes; a " + std::to_string(dim) +
                              "D body has none to hide them");
}

void read_quadrature(KeyReader& d, int dim, DiscretisationSpec& s) {
  if (auto q = d.optional_map("quadrature")) {
    s.order = q->integer("order", 3, 2, 10);
    s.cell_size = q->positive("cell_size", s.spacing);
    s.cut_levels = q->integer("cut_levels", 2, 0, 6);
    s.cut_arcs = q->choice("cut_cells", {"subdivide", "arcs"}, "subdivide") == "arcs";
    s.boundary_order = q->integer("boundary_order", s.order, 2, 10);
    s.vci = q->choice("correction", {"none", "vci"}, "none") == "vci";
    s.cell_mean_volumetric =
        q->choice("volumetric_strain", {"pointwise", "cell_mean"}, "pointwise") == "cell_mean";
    if (s.cell_mean_volumetric && dim < 2)
      q->error("volumetric_strain", "cell_mean is for plane_strain and solid_3d bodies");
    q->finish();
  } else {
    s.cell_size = s.spacing;
    s.boundary_order = s.order;
  }
}

} // namespace

DiscretisationSpec read_discretisation(KeyReader& r, int dim, const BoundingBox& bounds,
                                       const std::string& base_dir,
                                       const LinearSolverSpec& solver) {
  KeyReader d = r.map("discretisation");
  DiscretisationSpec s;
  s.method =
      d.choice("method", {"meshfree", "fem"}, "meshfree") == "fem" ? Method::Fem : Method::Meshfree;
  read_fem_options(d, dim, base_dir, s);
  double nodes_total = read_spacing(d, bounds, solver, s);
  for (KeyReader& f : d.map_list("refinement"))
    s.refinement.push_back(read_refinement(f, dim, bounds, solver, s, nodes_total));
  require_memory(d.path_of("spacing"), "nodes over the body and its refinements", nodes_total,
                 bytes_per_node(solver, nodes_total));
  read_shape_functions(d, dim, s);
  read_quadrature(d, dim, s);
  s.adapt = read_adapt(d, dim, s, solver);
  d.finish();
  return s;
}

} // namespace mf::spec
