// meshfree command line (docs/architecture.md, "The run contract"):
//   meshfree run PROBLEM.yaml [--out DIR | --restart DIR] [--set key.path=value ...]
//                [-- PETSc options]
//   meshfree check PROBLEM.yaml [--set key.path=value ...]
#include "meshfree/app/elastic_static.hpp"
#include "meshfree/app/elastoplastic_static.hpp"
#include "meshfree/app/model_problem_1d.hpp"
#include "meshfree/app/peridynamics.hpp"
#include "meshfree/app/sph_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/memory.hpp"
#include "meshfree/core/run_bounds.hpp"
#include "meshfree/explicit/pd_setup.hpp"
#include "meshfree/explicit/run_counts.hpp"
#include "meshfree/explicit/sph_setup.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/io/key_reader.hpp"
#include "meshfree/io/problem_spec.hpp"
#include "meshfree/io/unit_sanity.hpp"
#include "meshfree/quadrature/integration_points.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/sph/step.hpp"
#include "meshfree/stages/staged_run.hpp"
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <malloc.h>
#include <omp.h>
#include <optional>
#include <unistd.h>

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  meshfree run PROBLEM.yaml [--out DIR | --restart DIR] [--set key.path=value ...]\n"
    "               [-- PETSc options]\n"
    "  meshfree check PROBLEM.yaml [--set key.path=value ...]\n"
    "\n"
    "run    solves the problem and writes fields.h5/.xmf, history.csv, line_*.csv and\n"
    "       summary.json into DIR (default out/<problem name>/)\n"
    "       --restart DIR goes on from the last checkpoint in DIR/checkpoint\n"
    "check  validates the problem file and prints the discretisation it would use\n"
    "Options after '--' go to PETSc, e.g. -- -ksp_type cg -pc_type gamg -ksp_view\n";

/// An error as the user reads it: always one line (control characters shown escaped), and never
/// a whole file's worth however long a value it quotes.
std::string said(const std::exception& e) {
  return mf::io::one_line(e.what(), 2000);
}

struct Command {
  std::string verb, problem, out_dir, restart_dir;
  std::vector<std::string> overrides;
  std::vector<char*> petsc_argv; // program name + everything after "--"
};

Command parse(int argc, char** argv) {
  Command c;
  c.petsc_argv.push_back(argv[0]);
  int i = 1;
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") {
      for (++i; i < argc; ++i) c.petsc_argv.push_back(argv[i]);
      break;
    }
    if (a == "-h" || a == "--help") mf::fail("help");
    if (a == "--out" || a == "--restart" || a == "--set") {
      MF_REQUIRE(i + 1 < argc, a, " needs a value");
      (a == "--out"       ? c.out_dir
       : a == "--restart" ? c.restart_dir
                          : (c.overrides.emplace_back(), c.overrides.back())) = argv[++i];
    } else if (c.verb.empty()) {
      c.verb = a;
    } else if (c.problem.empty()) {
      c.problem = a;
    } else {
      mf::fail("unexpected argument '", a, "'");
    }
  }
  MF_REQUIRE(c.verb == "run" || c.verb == "check",
             c.verb.empty() ? "no command given" : "unknown command '" + c.verb + "'");
  MF_REQUIRE(!c.problem.empty(), "no problem file given");
  MF_REQUIRE(c.restart_dir.empty() || c.verb == "run", "--restart is an option of run");
  MF_REQUIRE(c.restart_dir.empty() || c.out_dir.empty() || c.out_dir == c.restart_dir, "--restart ",
             c.restart_dir, " with --out ", c.out_dir,
             ": a restart writes into the folder it restarts from");
  return c;
}

/// What a run of `spec` (one analysis) would build: its counts, time step and memory. Throws
/// what the run's set-up would throw.
void describe(const mf::io::ProblemSpec& spec) {
  if (spec.analysis == mf::io::Analysis::ModelProblem1D) {
    std::cout << "  1D model problem on [0, " << spec.model_1d.length << "], spacing "
              << spec.discretisation.spacing << "\n";
    return;
  }
  if (spec.analysis == mf::io::Analysis::Sph) {
    const mf::sph::Hydro h = mf::explicit_dynamics::build_sph(*spec.sph);
    int limiting = -1;
    const double dt = mf::sph::stable_step(h, &limiting);
    mf::explicit_dynamics::require_finite_run(
        mf::explicit_dynamics::planned_run(*spec.sph, h.particles.size(), dt), "out/" + spec.name);
    std::cout << "  sph: " << h.particles.size() << " particles in " << spec.sph->dimension
              << "D, first CFL step " << dt << " (particle " << limiting << "), about "
              << static_cast<long>(std::ceil(spec.sph->end_time / dt)) << " steps or more\n"
              << "  memory: "
              << mf::describe_bytes(h.particles.size() *
                                    mf::bytes_per::sph_particle(spec.sph->dimension))
              << " for the discretisation, besides " << mf::describe_bytes(mf::bytes_per::program)
              << " for the program\n";
    return;
  }
  if (spec.analysis == mf::io::Analysis::Peridynamics) {
    mf::PhaseTimer timer;
    const mf::explicit_dynamics::PdSetup setup = mf::explicit_dynamics::build_pd_setup(spec, timer);
    mf::explicit_dynamics::require_finite_run(mf::explicit_dynamics::planned_run(*spec.pd, setup),
                                              "out/" + spec.name);
    std::cout << "  peridynamics: " << setup.model.particles.size() << " particles, "
              << setup.model.bonds.pairs() << " bonds, horizon " << setup.model.horizon
              << "\n  time step " << setup.dt << " (" << setup.dt_limit << "), "
              << static_cast<long>(std::ceil(spec.pd->end_time / setup.dt)) << " steps\n"
              << "  memory: "
              << mf::describe_bytes(mf::bytes_per::pd_particle * setup.model.particles.size() +
                                    mf::bytes_per::pd_partner * setup.model.bonds.directed)
              << " for the discretisation, besides " << mf::describe_bytes(mf::bytes_per::program)
              << " for the program\n";
    return;
  }
  const auto& d = spec.discretisation;
  if (d.method == mf::io::Method::Fem) {
    const mf::fem::Mesh mesh = mf::implicit::read_fe_mesh(spec);
    std::cout << "  method: " << mf::implicit::describe_method(spec) << "\n"
              << "  mesh: " << mesh.element_count() << " " << mf::fem::element_name(mesh.type)
              << " elements, " << mesh.node_count() << " nodes (" << 2 * mesh.node_count()
              << " DOFs)\n"
              << "  memory: "
              << mf::describe_bytes(mf::bytes_per::galerkin_node * mesh.node_count())
              << " for the discretisation, besides " << mf::describe_bytes(mf::bytes_per::program)
              << " for the program\n";
  } else {
    const auto nodes = mf::geometry::generate_nodes(spec.domain, d.spacing, d.refinement);
    const auto pts = mf::quadrature::domain_points(
        spec.domain, d.cell_size, d.order, d.cut_levels,
        {d.spacing, d.refinement, d.cell_size / d.spacing, d.dilation.maxCoeff()}, d.cut_arcs);
    std::cout << "  method: " << mf::implicit::describe_method(spec) << "\n"
              << "  nodes: " << nodes.x.size() << " (" << 2 * nodes.x.size() << " DOFs)\n"
              << "  integration: " << pts.cell_count << " cells, " << pts.x.size() << " points\n"
              << "  memory: "
              << mf::describe_bytes(mf::bytes_per::galerkin_node_alone * nodes.x.size() +
                                    mf::bytes_per::galerkin_point * pts.x.size())
              << " for the discretisation, besides " << mf::describe_bytes(mf::bytes_per::program)
              << " for the program\n";
  }
  for (const auto& bc : spec.boundary) {
    double len = 0.0;
    for (const auto& p : mf::io::select_boundary(spec.domain, bc.on, bc.key_path))
      len += p.length();
    std::cout << "  boundary " << bc.name << ": " << (bc.constrains ? "displacement" : "traction")
              << " on length " << len << "\n";
  }
  for (const auto& step : spec.steps)
    std::cout << "  step " << step.name << ": " << step.increments << " increments\n";
}

/// An elastoplastic schedule's increments, each a Newton solve over every degree of freedom that
/// writes a field frame, a Gauss-point frame and a display-mesh frame, about 700 bytes per node
/// together (measured on plate_plastic_thesis, README.md "Running"): bounded by the time a run
/// may take here and by the disk of `folder`. The step whose increments pass a bound is named.
void require_increment_output(const mf::io::ProblemSpec& spec, const std::string& folder) {
  if (spec.analysis != mf::io::Analysis::ElastoplasticStatic) return;
  const mf::Vec2 size = spec.domain.bounds().size();
  const double h = spec.discretisation.spacing;
  const double nodes = (size.x() / h + 1.0) * (size.y() / h + 1.0);
  const std::size_t listed = spec.initial_stress ? 1 : 0; // "geostatic" is not in the file
  double frames = 1.0;
  for (std::size_t k = 0; k < spec.steps.size(); ++k) {
    frames += spec.steps[k].increments;
    if (k < listed) continue;
    const std::string key = "steps[" + std::to_string(k - listed) + "].increments";
    mf::require_run_time(key, "DOF-increments of the schedule so far", frames * 2.0 * nodes,
                         mf::work_per_second::galerkin_dof_increments);
    mf::require_disk(key, "field frames of the schedule so far", frames, 700.0 * nodes, folder);
  }
}

/// The explicit stage of a staged run, bounded as `check` bounds it (its particles and first step
/// built as its set-up builds them), before the preload runs: a stage that would never end is
/// refused as input, with its key path (stages[1].time.end), not after the preload's solve.
void require_finite_stages(const mf::io::ProblemSpec& spec, const std::string& folder) {
  for (const mf::io::ProblemSpec& stage : spec.stages) {
    if (stage.sph) {
      const mf::sph::Hydro h = mf::explicit_dynamics::build_sph(*stage.sph);
      mf::explicit_dynamics::require_finite_run(
          mf::explicit_dynamics::planned_run(*stage.sph, h.particles.size(),
                                             mf::sph::stable_step(h)),
          folder);
    } else if (stage.pd) {
      mf::PhaseTimer timer;
      const auto setup = mf::explicit_dynamics::build_pd_setup(stage, timer);
      mf::explicit_dynamics::require_finite_run(
          mf::explicit_dynamics::planned_run(*stage.pd, setup), folder);
    }
  }
}

/// Reads the problem and builds what its run builds before the first step or solve, stage by
/// stage; says "valid" only when all of it passed.
int check(const Command& c) {
  const mf::io::ProblemSpec spec = mf::io::read_problem(c.problem, c.overrides);
  mf::io::warn_unit_sanity(spec);
  if (spec.analysis != mf::io::Analysis::Staged) {
    describe(spec);
    require_increment_output(spec, "out/" + spec.name);
  } else {
    for (std::size_t k = 0; k < spec.stages.size(); ++k) {
      const mf::io::StageLink& l = spec.links[k];
      std::cout << "stage " << spec.stages[k].stage;
      if (l.from >= 0)
        std::cout << " from " << spec.stages[l.from].stage << " (" << l.hold.size()
                  << " condition(s) held, " << l.release.size() << " released)";
      std::cout << ":\n";
      describe(spec.stages[k]);
    }
  }
  std::cout << "problem " << spec.name << ": valid\n";
  return 0;
}

void log_phases(const mf::PhaseTimer& timer) {
  std::string phases;
  for (const auto& [name, s] : timer.phases())
    phases += " " + name + " " + std::to_string(s) + " s;";
  mf::log::info("wall time per phase:", phases);
}

/// The last instant a restarted run may hold: its (explicit stage's) end time, or no bound for an
/// implicit run, whose checkpoints count increments.
double restart_end(const mf::io::ProblemSpec& spec) {
  const mf::io::ProblemSpec& s =
      spec.analysis == mf::io::Analysis::Staged ? spec.stages.at(1) : spec;
  if (s.pd) return s.pd->end_time;
  if (s.sph) return s.sph->end_time;
  return std::numeric_limits<double>::infinity();
}

/// A refused restart's one line, naming the folder.
std::string refusal(const std::string& dir, const std::exception& e) {
  const std::string what = e.what();
  return what.rfind("--restart ", 0) == 0 ? what : "--restart " + dir + ": " + what;
}

/// A run that failed on its way (the reason is in its summary.json too): one line on stderr,
/// exit status 1.
int report_failure(const mf::solvers::PetscSession& session, const std::string& reason) {
  if (session.rank() == 0)
    std::cerr << "meshfree: run failed: " << mf::io::one_line(reason, 2000) << std::endl;
  return 1;
}

int run_in(Command& c, mf::solvers::PetscSession& session);

int run(Command& c) {
  int pargc = static_cast<int>(c.petsc_argv.size());
  c.petsc_argv.push_back(nullptr);
  char** pargv = c.petsc_argv.data();
  mf::solvers::PetscSession session(&pargc, &pargv);
  const int code = run_in(c, session);
  // After a failed HDF5 write (recorded by now, with its summary) the library's shutdown in
  // MPI_Finalize would crash on the file it cannot close: one process ends without it.
  if (mf::io::hdf5_write_failed() && session.size() == 1) {
    std::cout.flush();
    std::cerr.flush();
    std::_Exit(code);
  }
  return code;
}

int run_in(Command& c, mf::solvers::PetscSession& session) {
  mf::io::ProblemSpec spec;
  std::optional<mf::io::Restart> restart;
  try {
    spec = mf::io::read_problem(c.problem, c.overrides);
    mf::io::warn_unit_sanity(spec);
    // A finite-element mesh is input too: read and checked before anything is written.
    if (spec.discretisation.method == mf::io::Method::Fem) mf::implicit::read_fe_mesh(spec);
    if (!c.restart_dir.empty()) {
      MF_REQUIRE(spec.analysis == mf::io::Analysis::Peridynamics ||
                     spec.analysis == mf::io::Analysis::Sph ||
                     spec.analysis == mf::io::Analysis::Staged ||
                     spec.analysis == mf::io::Analysis::ElastoplasticStatic,
                 "--restart ", c.restart_dir,
                 ": only runs that go step by step write checkpoints (peridynamics, sph, "
                 "elastoplastic_static and staged runs)");
    }
  } catch (const std::exception& e) {
    if (session.rank() == 0) std::cerr << "meshfree: " << said(e) << std::endl;
    return 2;
  }
  const std::string dir = !c.restart_dir.empty() ? c.restart_dir
                          : c.out_dir.empty()    ? "out/" + spec.name
                                                 : c.out_dir;
  // The output folder is input too: one that cannot be written, or that a live run holds, is
  // refused before the run (its lock is held from here to the end).
  std::unique_ptr<mf::io::OutputDirectory> out;
  double unusable = 0.0;
  const bool explicit_run =
      spec.analysis == mf::io::Analysis::Peridynamics || spec.analysis == mf::io::Analysis::Sph;
  if (session.rank() == 0) try {
      require_increment_output(spec, dir);
      require_finite_stages(spec, dir);
      out = std::make_unique<mf::io::OutputDirectory>(dir, c.restart_dir.empty() ? "--out"
                                                                                 : "--restart");
      // An implicit run's folder is created now (an explicit run's at its first file, after its
      // set-up): a folder that cannot be made is refused as input, exit 2, as for every analysis.
      if (!explicit_run) out->open();
    } catch (const std::exception& e) {
      std::cerr << "meshfree: " << said(e) << std::endl;
      unusable = 1.0;
    }
  if (mf::distribution::Ranks::of(session.comm()).max(unusable) > 0.0) return 2;
  if (!c.restart_dir.empty()) {
    // The checkpoint must be this problem's, whole and undamaged (rank 0 reads every rank's file
    // through), before anything is written.
    double refused = 0.0;
    try {
      restart = mf::io::find_restart(dir, spec.settings, session.size(), restart_end(spec));
      if (session.rank() == 0) restart->verify();
      if (restart->threads != omp_get_max_threads() && session.rank() == 0)
        mf::log::warn("the checkpoint was written with ", restart->threads,
                      " OpenMP thread(s) and this run has ", omp_get_max_threads(),
                      ": the sums may differ in the last digits from the run it continues");
    } catch (const std::exception& e) {
      if (session.rank() == 0) std::cerr << "meshfree: " << refusal(dir, e) << std::endl;
      refused = 1.0;
    }
    if (mf::distribution::Ranks::of(session.comm()).max(refused) > 0.0) return 2;
  }
  const mf::io::Restart* from = restart ? &*restart : nullptr;
  int exit_code = 0;
  try {
    // An explicit run's set-up is input checking too (the particles of every block and region,
    // the bonds, the time step): its folder is created when the first file is written, and an
    // error before that is refused as input, with nothing written. Implicit runs keep what they
    // wrote up to a failure of their solve.
    mf::log::info("problem ", spec.name, ": ", spec.description);
    if (spec.analysis == mf::io::Analysis::ModelProblem1D) {
      if (session.rank() == 0) mf::app::model_problem_1d(spec, *out);
    } else if (spec.analysis == mf::io::Analysis::Peridynamics) {
      mf::explicit_dynamics::PdRunResult r = mf::app::run_peridynamics(
          spec, out.get(), mf::distribution::Ranks::of(session.comm()), dir, from);
      {
        mf::PhaseTimer::Scope scope(r.timer, "output");
        if (out) mf::app::write_pd_outputs(spec, r, *out);
      }
      log_phases(r.timer);
      if (r.status == "failed") exit_code = report_failure(session, r.stop_reason);
    } else if (spec.analysis == mf::io::Analysis::Sph) {
      mf::explicit_dynamics::SphRunResult r =
          mf::app::run_sph(spec, out.get(), mf::distribution::Ranks::of(session.comm()), dir, from);
      {
        mf::PhaseTimer::Scope scope(r.timer, "output");
        if (out) mf::app::write_sph_outputs(spec, r, *out);
      }
      log_phases(r.timer);
      if (r.status == "failed") exit_code = report_failure(session, r.stop_reason);
    } else if (spec.analysis == mf::io::Analysis::Staged) {
      const auto r = mf::stages::run_staged(spec, session, out.get(), dir, from);
      exit_code = r.exit_code == 1 ? report_failure(session, r.stop_reason) : r.exit_code;
    } else if (spec.analysis == mf::io::Analysis::ElastoplasticStatic) {
      const auto r = mf::app::elastoplastic_static(spec, session, out.get(), dir, from);
      log_phases(r.timer);
      if (r.status != "completed") exit_code = 3;
    } else {
      const auto r = mf::app::elastic_static(spec, session, out.get());
      log_phases(r.timer);
    }
    for (const std::string& option : session.unused_options())
      mf::log::warn("PETSc option ", option,
                    " was given but not used by this run (a typo, or an option of a solver this "
                    "analysis does not use)");
    if (out && exit_code == 0) {
      out->commit();
      mf::io::remove_checkpoints(dir); // the completed results supersede them
      mf::log::info("results in ", std::filesystem::absolute(dir).string());
    } else if (out) {
      const std::string kept = out->keep_unfinished(exit_code == 3 ? "stopped" : "failed");
      mf::log::info("the run did not complete; its files are in ",
                    std::filesystem::absolute(kept).string(),
                    ", and the last completed run's "
                    "results in ",
                    dir, " are untouched");
    }
  } catch (const std::exception& e) {
    // A CollectiveError reached every rank: each returns normally. Any other error may have
    // reached this rank only, and the others would wait for it forever: abort them.
    const bool everywhere = dynamic_cast<const mf::solvers::CollectiveError*>(&e) != nullptr;
    if (from && dynamic_cast<const mf::io::CheckpointRefused*>(&e)) {
      // Found while the state was read back: refused as input, and what this run wrote so far
      // (its staging folder) goes.
      std::cerr << "meshfree: " << refusal(dir, e) << std::endl;
      if (out) out->discard();
      if (session.size() > 1) mf::solvers::abort_every_rank(session.comm(), 2);
      return 2;
    }
    if (explicit_run && session.size() == 1 && dynamic_cast<const mf::Error*>(&e) && out &&
        !out->opened()) {
      std::cerr << "meshfree: " << said(e) << std::endl; // refused in set-up: nothing written
      return 2;
    }
    if (session.rank() == 0 || !everywhere)
      std::cerr << "meshfree: run failed"
                << (everywhere ? "" : " on rank " + std::to_string(session.rank())) << ": "
                << said(e) << std::endl;
    if (out) {
      // What the run wrote up to the failure is kept for diagnosis under DIR/failed, with a
      // summary that says why; a good result in DIR stays as it was.
      mf::io::Json summary;
      summary.set("problem", spec.name).set("status", "failed").set("error", e.what());
      try {
        out->set_prefix("");
        out->replace_summary(summary.str() + "\n");
        const std::string kept = out->keep_unfinished("failed");
        mf::log::info("the files written up to the failure are in ",
                      std::filesystem::absolute(kept).string());
      } catch (const std::exception& again) {
        std::cerr << "meshfree: cannot record the failure: " << said(again) << std::endl;
      }
    }
    if (session.size() > 1 && !everywhere) mf::solvers::abort_every_rank(session.comm(), 1);
    return 1;
  }
  return exit_code;
}

} // namespace

/// OpenMP threads that wait at the end of a loop sleep instead of spinning, unless the user chose
/// a policy: with another job on one of the cores a spinning team waits for its slowest thread
/// at every loop, a sleeping one gives the core away. libgomp reads OMP_WAIT_POLICY when it is
/// loaded, before main, so the program runs itself again once with the policy set (on failure it
/// goes on with the default).
void wait_passively(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  setenv("OMP_WAIT_POLICY", "passive", 1);
  execv("/proc/self/exe", argv);
}

/// Freed memory stays with the process instead of going back to the system. glibc serves large
/// blocks by mmap and unmaps them on free, so every large vector (a shape table, a solver's work
/// space) is paged in afresh, and the first touch of a page is what costs on virtual machines,
/// more for memory the host has taken back than for memory just freed; keeping it makes large
/// assemblies faster at the same peak memory (measured in README.md, "Running").
void keep_freed_memory() {
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

int main(int argc, char** argv) {
  wait_passively(argv);
  keep_freed_memory();
  // A write past a file-size limit (ulimit -f) fails with EFBIG and is reported as a failed
  // write, with its summary, instead of killing the run with nothing said.
  std::signal(SIGXFSZ, SIG_IGN);
  Command c;
  try {
    c = parse(argc, argv);
  } catch (const mf::Error& e) {
    const bool help = std::strcmp(e.what(), "help") == 0;
    (help ? std::cout : std::cerr)
        << (help ? "" : std::string("meshfree: ") + said(e) + "\n") << kUsage;
    return help ? 0 : 2;
  }
  try {
    return c.verb == "check" ? check(c) : run(c);
  } catch (const std::exception& e) {
    std::cerr << "meshfree: " << said(e) << std::endl;
    return 2;
  }
}
