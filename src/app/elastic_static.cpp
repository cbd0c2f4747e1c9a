#include "meshfree/app/elastic_static.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/coupling.hpp"
#include "meshfree/implicit/elasticity.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include <algorithm>
#include <omp.h>

namespace mf::app {

namespace {

using implicit::Csr;
using implicit::ShapeTable;

/// The points a rank integrates: every point whose support holds one of its nodes, so that its
/// block rows are complete without communication (points near a partition boundary are
/// integrated by both neighbours, each keeping its own rows). `counted` marks the points whose
/// lowest-numbered node it owns: sums over the body (errors, reactions) take those only, so
/// each point counts once.
struct RankPoints {
  std::vector<int> rows;
  std::vector<char> counted;
};

/// Integration points of one boundary condition and their support lists.
struct ConditionPoints {
  const io::BoundaryCondition* bc = nullptr;
  quadrature::BoundaryPoints points;
  Csr support;
  RankPoints mine;          // points this rank integrates
  std::vector<Vec2> values; // ubar or traction at each of those rows
};

/// Traction sigma . n from Voigt stress [sxx, syy, sxy].
Vec2 traction(const Vec3& s, const Vec2& n) {
  return {s(0) * n.x() + s(2) * n.y(), s(2) * n.x() + s(1) * n.y()};
}

/// Prescribed displacement or traction at the given rows of a condition's points.
std::vector<Vec2> condition_values(const io::ProblemSpec& spec, const io::BoundaryCondition& bc,
                                   const quadrature::BoundaryPoints& pts,
                                   const std::vector<int>& rows) {
  const materials::IsotropicElastic m =
      materials::plane_stress_equivalent(spec.material, spec.model);
  std::vector<Vec2> out;
  for (int r : rows) {
    if (bc.constrains)
      out.push_back(bc.value_from_exact ? verification::exact_displacement(*spec.exact, m, pts.x[r])
                                        : bc.value);
    else
      out.push_back(
          bc.traction_from_exact
              ? traction(verification::exact_stress(*spec.exact, m, pts.x[r]), pts.normal[r])
              : bc.traction);
  }
  return out;
}

RankPoints rank_points(const Csr& support, solvers::OwnedRange own, int node_count,
                       const solvers::PetscSession& s) {
  RankPoints p;
  for (int r = 0; r < support.rows(); ++r) {
    const int* first = support.index.data() + support.offset[r];
    const int* last = support.index.data() + support.offset[r + 1];
    // lists are sorted, so the lowest node is the first one
    if (std::any_of(first, last, [&](int I) { return own.owns(I); })) {
      p.rows.push_back(r);
      p.counted.push_back(solvers::owner_of(*first, node_count, s.size()) == s.rank());
    }
  }
  return p;
}

/// Fields at arbitrary points (nodes, line samples): u^h, stress, szz.
void evaluate_fields(const implicit::MeshfreeSpace& space, const io::ProblemSpec& spec,
                     const std::vector<Vec2>& x, const std::vector<double>& d, std::vector<Vec2>& u,
                     std::vector<Vec3>& stress, std::vector<double>& szz) {
  const Csr support = space.support_lists(x);
  std::vector<int> all(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) all[i] = static_cast<int>(i);
  const ShapeTable t = space.shape_table(x, all, support, true);
  const Mat3 C = materials::elastic_matrix(spec.material, spec.model);
  u.resize(x.size());
  stress.resize(x.size());
  szz.resize(x.size());
  for (int r = 0; r < t.rows(); ++r) {
    u[r] = implicit::displacement_at(t, r, d);
    stress[r] = C * implicit::strain_at(t, r, d);
    szz[r] = materials::out_of_plane_stress(spec.material, spec.model, stress[r]);
  }
}

} // namespace

std::string describe_method(const io::DiscretisationSpec& d) {
  const auto& s = d.shape;
  std::string m = s.approximation == kernels::Approximation::ReproducingKernel    ? "RK"
                  : s.approximation == kernels::Approximation::MovingLeastSquares ? "MLS/EFG"
                                                                                  : "SPH";
  m += s.basis == kernels::Basis::Linear ? " Galerkin, linear basis, "
                                         : " Galerkin, quadratic basis, ";
  m += s.window.type == kernels::WindowType::CubicSpline     ? "cubic B-spline"
       : s.window.type == kernels::WindowType::QuarticSpline ? "quartic spline"
                                                             : "truncated Gaussian";
  m += s.support == kernels::SupportShape::Circular ? " window, circular supports"
                                                    : " window, rectangular supports";
  return m;
}

ElasticResult solve_elastic_static(const io::ProblemSpec& spec,
                                   const solvers::PetscSession& session) {
  ElasticResult R;
  const io::DiscretisationSpec& disc = spec.discretisation;
  const double t = spec.thickness;

  // 1. Nodes and their supports.
  PhaseTimer& timer = R.timer;
  std::unique_ptr<implicit::MeshfreeSpace> space;
  {
    PhaseTimer::Scope scope(timer, "nodes");
    space = std::make_unique<implicit::MeshfreeSpace>(
        geometry::generate_nodes(spec.domain, disc.spacing, disc.refinement), disc.shape,
        disc.dilation);
  }
  const int N = space->node_count();
  R.nodes = N;
  R.dofs = 2 * N;
  log::info("nodes: ", N, " (", R.dofs, " DOFs), ", describe_method(disc));

  // 2. Integration points: background cells over the body, Gauss points on loaded and
  // constrained boundary pieces.
  quadrature::DomainPoints dp;
  std::vector<ConditionPoints> bcs(spec.boundary.size());
  {
    PhaseTimer::Scope scope(timer, "quadrature");
    const quadrature::CellSizing sizing{disc.spacing, disc.refinement,
                                        disc.cell_size / disc.spacing, disc.dilation.maxCoeff()};
    dp =
        quadrature::domain_points(spec.domain, disc.cell_size, disc.order, disc.cut_levels, sizing);
    for (std::size_t b = 0; b < spec.boundary.size(); ++b) {
      bcs[b].bc = &spec.boundary[b];
      const auto pieces =
          io::select_boundary(spec.domain, spec.boundary[b].on, spec.boundary[b].key_path);
      bcs[b].points =
          quadrature::boundary_points(pieces, disc.cell_size, disc.boundary_order, sizing);
      R.boundary_points += static_cast<int>(bcs[b].points.x.size());
    }
  }
  R.domain_points = static_cast<int>(dp.x.size());
  R.cells = dp.cell_count;
  log::info("integration: ", R.cells, " background cells, ", R.domain_points, " domain points, ",
            R.boundary_points, " boundary points");

  // 3. Neighbours: support lists of every point, and the exact matrix pattern of owned rows.
  const solvers::OwnedRange own = solvers::owned_nodes(N, session.rank(), session.size());
  Csr dsupport;
  RankPoints dmine;
  implicit::RowPattern pattern;
  {
    PhaseTimer::Scope scope(timer, "neighbours");
    dsupport = space->support_lists(dp.x);
    std::vector<const Csr*> lists{&dsupport};
    for (auto& c : bcs) {
      c.support = space->support_lists(c.points.x);
      if (c.bc->constrains) lists.push_back(&c.support);
    }
    const auto require_covered = [](const Csr& support, const std::vector<Vec2>& x) {
      for (int r = 0; r < support.rows(); ++r)
        MF_REQUIRE(support.size(r) > 0, "integration point (", x[r].x(), ", ", x[r].y(),
                   ") is covered by no node: raise discretisation.dilation");
    };
    require_covered(dsupport, dp.x);
    for (const auto& c : bcs) require_covered(c.support, c.points.x);
    pattern = implicit::coupling_pattern(lists, N, own.begin, own.end);
    dmine = rank_points(dsupport, own, N, session);
    for (auto& c : bcs) c.mine = rank_points(c.support, own, N, session);
  }
  R.mean_support = static_cast<double>(dsupport.index.size()) / std::max(1, dsupport.rows());

  // 4. Shape functions at this rank's points.
  ShapeTable dtable;
  std::vector<ShapeTable> btables(bcs.size());
  {
    PhaseTimer::Scope scope(timer, "shape_functions");
    session.collective([&] {
      dtable = space->shape_table(dp.x, dmine.rows, dsupport, true);
      for (std::size_t b = 0; b < bcs.size(); ++b)
        btables[b] = space->shape_table(bcs[b].points.x, bcs[b].mine.rows, bcs[b].support, false);
    });
  }

  // 5. Assembly of K d = f.
  implicit::BlockRows rows(std::move(pattern));
  const auto add_matrix = [&](const int* nodes, int n, const double* v) {
    rows.add_matrix(nodes, n, v);
  };
  const auto add_vector = [&](const int* nodes, int n, const double* v) {
    rows.add_vector(nodes, n, v);
  };
  const Mat3 C = materials::elastic_matrix(spec.material, spec.model);
  const materials::IsotropicElastic exact_mat =
      materials::plane_stress_equivalent(spec.material, spec.model);
  {
    PhaseTimer::Scope scope(timer, "assembly");
    std::vector<double> w(dmine.rows.size());
    for (std::size_t k = 0; k < w.size(); ++k) w[k] = dp.weight[dmine.rows[k]] * t;
    implicit::add_stiffness(dtable, w, C, add_matrix);
    if (!spec.body_force.isZero())
      implicit::add_load(dtable, w, std::vector<Vec2>(w.size(), spec.body_force), add_vector);
    for (std::size_t b = 0; b < bcs.size(); ++b) {
      const io::BoundaryCondition& bc = *bcs[b].bc;
      const auto& pts = bcs[b].points;
      std::vector<double> bw;
      for (int r : bcs[b].mine.rows) bw.push_back(pts.weight[r] * t);
      bcs[b].values = condition_values(spec, bc, pts, bcs[b].mine.rows);
      const auto& val = bcs[b].values;
      if (bc.constrains)
        implicit::add_penalty(btables[b], bw, bc.mask, bc.penalty, val, add_matrix, add_vector);
      else
        implicit::add_load(btables[b], bw, val, add_vector);
    }
  }
  std::unique_ptr<solvers::BlockLinearSystem> system;
  {
    PhaseTimer::Scope scope(timer, "solver_setup");
    const implicit::RowPattern& p = rows.pattern();
    system = std::make_unique<solvers::BlockLinearSystem>(
        session.comm(), N, own, p.offset, p.column, rows.values(), rows.rhs(), /*spd=*/true);
  }
  R.matrix_nonzeros = system->global_nonzeros();
  log::info("matrix: ", R.dofs, " x ", R.dofs, ", ", static_cast<long>(R.matrix_nonzeros),
            " nonzeros");

  // 6. Solve.
  {
    PhaseTimer::Scope scope(timer, "solve");
    R.solve = system->solve();
    R.parameters = system->solution_everywhere();
  }
  log::info("solved with ", R.solve.solver, ": ", R.solve.reason_name, ", relative residual ",
            R.solve.residual_norm);

  // 7. Post-processing: errors against the exact solution, reactions, constraint violation,
  // fields at the nodes and on sample lines.
  {
    PhaseTimer::Scope scope(timer, "postprocess");
    const auto& d = R.parameters;
    for (double v : d)
      MF_REQUIRE(std::isfinite(v), "the solution contains NaN or Inf: the system is singular; "
                                   "check the boundary conditions");
    if (spec.exact) {
      double sums[4] = {0, 0, 0, 0}; // |e_u|^2, |u|^2, e_eps.C.e_eps, eps.C.eps
      const Mat3 Cinv = C.inverse();
      for (int k = 0; k < dtable.rows(); ++k) {
        if (!dmine.counted[k]) continue;
        const Vec2& x = dp.x[dmine.rows[k]];
        const double w = dp.weight[dmine.rows[k]];
        const Vec2 ue = verification::exact_displacement(*spec.exact, exact_mat, x);
        const Vec3 ee = Cinv * verification::exact_stress(*spec.exact, exact_mat, x);
        const Vec2 eu = implicit::displacement_at(dtable, k, d) - ue;
        const Vec3 eps = implicit::strain_at(dtable, k, d) - ee;
        sums[0] += w * eu.squaredNorm();
        sums[1] += w * ue.squaredNorm();
        sums[2] += w * eps.dot(C * eps);
        sums[3] += w * ee.dot(C * ee);
      }
      MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, session.comm());
      R.error_l2 = std::sqrt(sums[0] / sums[1]);
      R.error_energy = std::sqrt(sums[2] / sums[3]);
    }
    for (std::size_t b = 0; b < bcs.size(); ++b) {
      const io::BoundaryCondition& bc = *bcs[b].bc;
      BoundaryReport rep;
      rep.name = bc.name;
      rep.constraint = bc.constrains;
      double local[3] = {0, 0, 0};
      const auto& pts = bcs[b].points;
      for (int k = 0; k < btables[b].rows(); ++k) {
        if (!bcs[b].mine.counted[k]) continue;
        const double w = pts.weight[bcs[b].mine.rows[k]] * t;
        if (bc.constrains) {
          const Vec2 gap = (implicit::displacement_at(btables[b], k, d) - bcs[b].values[k])
                               .cwiseProduct(bc.mask);
          local[0] -= bc.penalty * w * gap.x(); // penalty force on the body
          local[1] -= bc.penalty * w * gap.y();
          local[2] = std::max(local[2], gap.norm());
        } else { // applied force: the integral of the traction
          local[0] += w * bcs[b].values[k].x();
          local[1] += w * bcs[b].values[k].y();
        }
      }
      double global[2];
      MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, session.comm());
      MPI_Allreduce(MPI_IN_PLACE, &local[2], 1, MPI_DOUBLE, MPI_MAX, session.comm());
      rep.force = Vec2(global[0], global[1]);
      rep.violation_max = local[2];
      R.violation_max = std::max(R.violation_max, rep.violation_max);
      R.boundary.push_back(rep);
    }
    session.collective([&] {
      if (session.rank() != 0) return;
      R.node_x = space->nodes().x;
      evaluate_fields(*space, spec, R.node_x, d, R.node_u, R.node_stress, R.node_szz);
      double umax = 0.0;
      for (const auto& u : R.node_u) umax = std::max(umax, u.norm());
      R.violation_relative = umax > 0.0 ? R.violation_max / umax : 0.0;
      for (const auto& line : spec.lines) {
        LineSample s;
        for (int k = 0; k < line.points; ++k) {
          const double f = static_cast<double>(k) / (line.points - 1);
          const Vec2 x = line.from + f * (line.to - line.from);
          if (!spec.domain.contains(x, 1e-9)) continue;
          s.x.push_back(x);
          s.s.push_back(f * (line.to - line.from).norm());
        }
        std::vector<double> szz;
        if (!s.x.empty()) evaluate_fields(*space, spec, s.x, d, s.u, s.stress, szz);
        R.lines.emplace_back(line.name, std::move(s));
      }
    });
  }
  return R;
}

void write_elastic_outputs(const io::ProblemSpec& spec, const ElasticResult& r,
                           const solvers::PetscSession& session, io::OutputDirectory& out) {
  if (session.rank() != 0) return;
  const materials::IsotropicElastic exact_mat =
      materials::plane_stress_equivalent(spec.material, spec.model);
  io::FieldStep step;
  step.time = 1.0;
  std::vector<double> sxx, syy, sxy, vm, vol, rad;
  for (std::size_t i = 0; i < r.node_x.size(); ++i) {
    sxx.push_back(r.node_stress[i](0));
    syy.push_back(r.node_stress[i](1));
    sxy.push_back(r.node_stress[i](2));
    vm.push_back(materials::von_mises(r.node_stress[i], r.node_szz[i]));
  }
  std::vector<Vec2> params(r.node_x.size());
  for (std::size_t i = 0; i < params.size(); ++i)
    params[i] = Vec2(r.parameters[2 * i], r.parameters[2 * i + 1]);
  step.vectors = {{"displacement", r.node_u}, {"nodal_parameters", params}};
  step.scalars = {{"stress_xx", sxx},
                  {"stress_yy", syy},
                  {"stress_xy", sxy},
                  {"stress_zz", r.node_szz},
                  {"von_mises", vm}};
  if (spec.exact) {
    std::vector<Vec2> ue;
    for (const auto& x : r.node_x)
      ue.push_back(verification::exact_displacement(*spec.exact, exact_mat, x));
    step.vectors.emplace_back("displacement_exact", ue);
  }
  out.write_fields(r.node_x, {step});

  for (const auto& [name, s] : r.lines) {
    std::vector<std::string> header{"s",  "x",         "y",         "ux",
                                    "uy", "stress_xx", "stress_yy", "stress_xy"};
    if (spec.exact)
      header.insert(header.end(), {"ux_exact", "uy_exact", "stress_xx_exact", "stress_yy_exact",
                                   "stress_xy_exact"});
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      std::vector<double> row{s.s[k],     s.x[k].x(),     s.x[k].y(),     s.u[k].x(),
                              s.u[k].y(), s.stress[k](0), s.stress[k](1), s.stress[k](2)};
      if (spec.exact) {
        const Vec2 ue = verification::exact_displacement(*spec.exact, exact_mat, s.x[k]);
        const Vec3 se = verification::exact_stress(*spec.exact, exact_mat, s.x[k]);
        row.insert(row.end(), {ue.x(), ue.y(), se(0), se(1), se(2)});
      }
      rows.push_back(row);
    }
    out.write_csv("line_" + name + ".csv", header, rows);
  }

  double umax = 0.0, vmmax = 0.0;
  for (const auto& u : r.node_u) umax = std::max(umax, u.norm());
  for (double v : vm) vmmax = std::max(vmmax, v);
  std::vector<std::string> header{"step", "load_factor"};
  std::vector<double> row{1.0, 1.0};
  for (const auto& b : r.boundary) {
    const std::string kind = b.constraint ? "reaction_" : "load_";
    header.push_back(kind + b.name + "_x");
    header.push_back(kind + b.name + "_y");
    row.push_back(b.force.x());
    row.push_back(b.force.y());
  }
  header.insert(header.end(), {"max_displacement", "max_von_mises", "solver_iterations"});
  row.insert(row.end(), {umax, vmmax, static_cast<double>(r.solve.iterations)});
  out.write_csv("history.csv", header, {row});

  io::Json counts, times, results, bnd, solver;
  counts.set("nodes", r.nodes)
      .set("dofs", r.dofs)
      .set("background_cells", r.cells)
      .set("domain_points", r.domain_points)
      .set("boundary_points", r.boundary_points)
      .set("mean_nodes_per_point", r.mean_support)
      .set("matrix_nonzeros", r.matrix_nonzeros)
      .set("steps", 1)
      .set("newton_iterations", 0);
  for (const auto& [name, sec] : r.timer.phases()) times.set(name, sec);
  times.set("total", r.timer.total());
  solver.set("type", r.solve.solver)
      .set("iterations", r.solve.iterations)
      .set("reason", r.solve.reason_name)
      .set("relative_residual", r.solve.residual_norm);
  for (const auto& b : r.boundary) {
    io::Json j;
    j.set("kind", b.constraint ? "displacement" : "traction");
    j.set(b.constraint ? "reaction" : "applied_force",
          std::vector<double>{b.force.x(), b.force.y()});
    if (b.constraint) j.set("violation_max", b.violation_max);
    bnd.set(b.name, j);
  }
  results.set("max_displacement", umax)
      .set("max_von_mises", vmmax)
      .set("constraint_violation_max", r.violation_max)
      .set("constraint_violation_relative", r.violation_relative)
      .set("boundary", bnd);
  if (spec.exact)
    results.set("error_l2_relative", r.error_l2).set("error_energy_relative", r.error_energy);
  io::Json summary;
  summary.set("problem", spec.name)
      .set("description", spec.description)
      .set("units", spec.units)
      .set("analysis", "elastic_static")
      .set("method", describe_method(spec.discretisation))
      .set("status", "completed")
      .set("mpi_ranks", session.size())
      .set("openmp_threads", omp_get_max_threads())
      .set("counts", counts)
      .set("solver", solver)
      .set("time_s", times)
      .set("results", results);
  out.write_text("summary.json", summary.str() + "\n");
}

} // namespace mf::app
