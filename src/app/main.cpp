// meshfree command line (docs/architecture.md, "The run contract"):
//   meshfree run PROBLEM.yaml [--out DIR | --restart DIR] [--set key.path=value ...]
//                [-- PETSc options]
//   meshfree check PROBLEM.yaml [--set key.path=value ...]
#include "meshfree/app/analysis.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/core/process_setup.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/spec/key_reader.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/spec/unit_sanity.hpp"
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <omp.h>
#include <optional>

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
  return mf::spec::one_line(e.what(), 2000);
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

/// Reads the problem and builds what its run builds before the first step or solve, stage by
/// stage; says "valid" only when all of it passed.
int check(const Command& c) {
  const mf::spec::ProblemSpec spec = mf::spec::read_problem(c.problem, c.overrides);
  mf::spec::warn_unit_sanity(spec);
  const mf::app::AnalysisEntry& entry = mf::app::entry_of(spec.analysis);
  (entry.check ? entry.check : entry.describe)(spec);
  std::cout << "problem " << spec.name << ": valid\n";
  return 0;
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
    std::cerr << "meshfree: run failed: " << mf::spec::one_line(reason, 2000) << std::endl;
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

/// What the run wrote up to a failure is kept for diagnosis under DIR/failed, with a summary
/// that says why; a good result in DIR stays as it was.
void keep_failed(mf::io::OutputDirectory& out, const mf::spec::ProblemSpec& spec,
                 const std::exception& e) {
  mf::io::Json summary;
  summary.set("problem", spec.name).set("status", "failed").set("error", e.what());
  try {
    out.set_prefix("");
    out.replace_summary(summary.str() + "\n");
    const std::string kept = out.keep_unfinished("failed");
    mf::log::info("the files written up to the failure are in ",
                  std::filesystem::absolute(kept).string());
  } catch (const std::exception& again) {
    std::cerr << "meshfree: cannot record the failure: " << said(again) << std::endl;
  }
}

/// The problem of a run, read and checked; a restart only of an analysis that writes checkpoints.
const mf::app::AnalysisEntry& read_for_run(const Command& c, mf::spec::ProblemSpec& spec) {
  spec = mf::spec::read_problem(c.problem, c.overrides);
  mf::spec::warn_unit_sanity(spec);
  const mf::app::AnalysisEntry& entry = mf::app::entry_of(spec.analysis);
  MF_REQUIRE(c.restart_dir.empty() || entry.checkpoints, "--restart ", c.restart_dir,
             ": only runs that go step by step write checkpoints (",
             mf::app::checkpointing_analyses(), " runs)");
  return entry;
}

/// The output folder is input too: one that cannot be written, or that a live run holds, is
/// refused before the run (its lock is held from here to the end), as is what the analysis
/// refuses before writing (a mesh, a run that would not end). Rank 0 takes the folder; false on
/// every rank when it was refused.
bool take_output(const Command& c, const mf::solvers::PetscSession& session,
                 const mf::spec::ProblemSpec& spec, const mf::app::AnalysisEntry& entry,
                 const std::string& dir, std::unique_ptr<mf::io::OutputDirectory>& out) {
  double unusable = 0.0;
  if (session.rank() == 0) try {
      if (entry.admit) entry.admit(spec, dir);
      out = std::make_unique<mf::io::OutputDirectory>(dir, c.restart_dir.empty() ? "--out"
                                                                                 : "--restart");
      // An implicit run's folder is created now (an explicit run's at its first file, after its
      // set-up): a folder that cannot be made is refused as input, exit 2, as for every analysis.
      if (!entry.folder_at_first_file) out->open();
    } catch (const std::exception& e) {
      std::cerr << "meshfree: " << said(e) << std::endl;
      unusable = 1.0;
    }
  return mf::distribution::Ranks::of(session.comm()).max(unusable) == 0.0;
}

/// The checkpoint must be this problem's, whole and undamaged (rank 0 reads every rank's file
/// through), before anything is written. False on every rank when it was refused.
bool take_restart(const std::string& dir, const mf::solvers::PetscSession& session,
                  const mf::spec::ProblemSpec& spec, const mf::app::AnalysisEntry& entry,
                  std::optional<mf::io::Restart>& restart) {
  double refused = 0.0;
  try {
    restart = mf::io::find_restart(dir, spec.settings, session.size(), entry.end_time(spec));
    if (session.rank() == 0) restart->verify();
    if (restart->threads != omp_get_max_threads() && session.rank() == 0)
      mf::log::warn("the checkpoint was written with ", restart->threads,
                    " OpenMP thread(s) and this run has ", omp_get_max_threads(),
                    ": the sums may differ in the last digits from the run it continues");
  } catch (const std::exception& e) {
    if (session.rank() == 0) std::cerr << "meshfree: " << refusal(dir, e) << std::endl;
    refused = 1.0;
  }
  return mf::distribution::Ranks::of(session.comm()).max(refused) == 0.0;
}

/// A completed run's results replace the folder's (and its checkpoints go); an unfinished run's
/// files are kept beside them, under DIR/stopped or DIR/failed.
void settle_output(mf::io::OutputDirectory* out, int exit_code, const std::string& dir) {
  if (!out) return;
  if (exit_code == 0) {
    out->commit();
    mf::io::remove_checkpoints(dir); // the completed results supersede them
    mf::log::info("results in ", std::filesystem::absolute(dir).string());
    return;
  }
  const std::string kept = out->keep_unfinished(exit_code == 3 ? "stopped" : "failed");
  mf::log::info("the run did not complete; its files are in ",
                std::filesystem::absolute(kept).string(),
                ", and the last completed run's results in ", dir, " are untouched");
}

/// A run that threw. A CollectiveError reached every rank: each returns normally. Any other error
/// may have reached this rank only, and the others would wait for it forever: they are aborted.
int end_thrown_run(const std::exception& e, const mf::solvers::PetscSession& session,
                   const mf::spec::ProblemSpec& spec, const mf::app::AnalysisEntry& entry,
                   mf::io::OutputDirectory* out, const std::string& dir, bool restarted) {
  const bool everywhere = dynamic_cast<const mf::solvers::CollectiveError*>(&e) != nullptr;
  if (restarted && dynamic_cast<const mf::io::CheckpointRefused*>(&e)) {
    // Found while the state was read back: refused as input, and what this run wrote so far
    // (its staging folder) goes.
    std::cerr << "meshfree: " << refusal(dir, e) << std::endl;
    if (out) out->discard();
    if (session.size() > 1) mf::solvers::abort_every_rank(session.comm(), 2);
    return 2;
  }
  if (entry.folder_at_first_file && session.size() == 1 && dynamic_cast<const mf::Error*>(&e) &&
      out && !out->opened()) {
    std::cerr << "meshfree: " << said(e) << std::endl; // refused in set-up: nothing written
    return 2;
  }
  if (session.rank() == 0 || !everywhere)
    std::cerr << "meshfree: run failed"
              << (everywhere ? "" : " on rank " + std::to_string(session.rank())) << ": " << said(e)
              << std::endl;
  if (out) keep_failed(*out, spec, e);
  if (session.size() > 1 && !everywhere) mf::solvers::abort_every_rank(session.comm(), 1);
  return 1;
}

int run_in(Command& c, mf::solvers::PetscSession& session) {
  mf::spec::ProblemSpec spec;
  const mf::app::AnalysisEntry* entry = nullptr;
  try {
    entry = &read_for_run(c, spec);
  } catch (const std::exception& e) {
    if (session.rank() == 0) std::cerr << "meshfree: " << said(e) << std::endl;
    return 2;
  }
  const std::string dir = !c.restart_dir.empty() ? c.restart_dir
                          : c.out_dir.empty()    ? "out/" + spec.name
                                                 : c.out_dir;
  std::unique_ptr<mf::io::OutputDirectory> out;
  if (!take_output(c, session, spec, *entry, dir, out)) return 2;
  std::optional<mf::io::Restart> restart;
  if (!c.restart_dir.empty() && !take_restart(dir, session, spec, *entry, restart)) return 2;
  try {
    // An explicit run's set-up is input checking too (the particles of every block and region,
    // the bonds, the time step): its folder is created when the first file is written, and an
    // error before that is refused as input, with nothing written. Implicit runs keep what they
    // wrote up to a failure of their solve.
    mf::log::info("problem ", spec.name, ": ", spec.description);
    const mf::app::RunOutcome r =
        entry->run({spec, session, out.get(), dir, restart ? &*restart : nullptr});
    const int exit_code = r.exit_code == 1 ? report_failure(session, r.reason) : r.exit_code;
    for (const std::string& option : session.unused_options())
      mf::log::warn("PETSc option ", option,
                    " was given but not used by this run (a typo, or an option of a solver this "
                    "analysis does not use)");
    settle_output(out.get(), exit_code, dir);
    return exit_code;
  } catch (const std::exception& e) {
    return end_thrown_run(e, session, spec, *entry, out.get(), dir, restart.has_value());
  }
}

} // namespace

int main(int argc, char** argv) {
  mf::keep_freed_memory();
  mf::single_process_mpi();
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
