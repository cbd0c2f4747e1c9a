#include "meshfree/stages/staged_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/implicit/solid_elastoplastic.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include <memory>
#include <omp.h>

namespace mf::stages {

namespace {

/// Whether the explicit stage sums in global-id order (discretisation.deterministic): its fields
/// are then those of one rank, and so must be the preload it starts from.
bool deterministic_sums(const spec::ProblemSpec& event) {
  return event.is_sph() ? event.sph().numerics.deterministic
                        : event.is_pd() && event.pd().deterministic;
}

/// Over several ranks with deterministic sums, the preload is solved whole on every rank, on
/// this rank alone (PETSc assembly, MUMPS and Newton as on one rank), so that every rank holds
/// the one-rank preload bit for bit: a preload spread over the ranks sums its assembly and its
/// factorisation in another order, and Newton stops at the penalty terms' round-off floor in
/// another state. Null otherwise: the preload is spread over the ranks.
std::unique_ptr<const solvers::PetscSession> preload_alone(const spec::ProblemSpec& event,
                                                           const solvers::PetscSession& session) {
  if (session.size() == 1 || !deterministic_sums(event)) return nullptr;
  log::info("preload: solved whole on each of the ", session.size(),
            " ranks (deterministic sums: the run is the one-rank run), not spread over them");
  return solvers::PetscSession::this_rank_alone();
}

/// The preload solved and written under its stage's prefix, as the explicit stage sees it.
struct SolvedPreload {
  implicit::ElastoplasticResult plane;
  implicit::SolidElastoplasticResult solid;
  std::unique_ptr<Preload> view;
  std::string status, stop_reason;
  io::Json section; // the preload's section of summary.json
  PhaseTimer timer;
};

/// A plane preload (GalerkinSpec), every increment's nodal parameters kept.
void solve_plane(SolvedPreload& s, spec::ProblemSpec& preload, const solvers::PetscSession& session,
                 const solvers::PetscSession& alone_or_all, bool alone, io::OutputDirectory* out) {
  preload.galerkin().record_increment_parameters = true; // each particle is carried through them
  s.plane = implicit::solve_elastoplastic_static(preload, alone_or_all, out);
  if (alone) s.plane.memory = solvers::peak_memory(session.comm()); // every rank holds it whole
  if (out) implicit::write_elastoplastic_outputs(preload, s.plane, alone_or_all, *out);
  const implicit::IncrementRecord& last = s.plane.increments.back();
  s.section.set("analysis", "elastoplastic_static")
      .set("status", s.plane.status)
      .set("increments", static_cast<long>(s.plane.increments.size()) - 1)
      .set("max_plastic_strain", last.max_plastic_strain)
      .set("plastic_points", last.plastic_points)
      .set("equilibrium_error", last.equilibrium_error)
      .set("seconds", s.plane.timer.total());
  s.status = s.plane.status, s.stop_reason = s.plane.stop_reason, s.timer = s.plane.timer;
  s.view = std::make_unique<PlanePreload>(preload, s.plane);
}

/// A 3D preload (SolidSpec), every increment's nodal parameters kept.
void solve_solid(SolvedPreload& s, spec::ProblemSpec& preload, const solvers::PetscSession& session,
                 const solvers::PetscSession& alone_or_all, bool alone, io::OutputDirectory* out) {
  preload.solid().record_increment_parameters = true;
  s.solid = implicit::solve_solid_elastoplastic(preload, alone_or_all, out);
  if (alone) s.solid.memory = solvers::peak_memory(session.comm());
  if (out) implicit::write_solid_elastoplastic_outputs(preload, s.solid, alone_or_all, *out);
  const implicit::IncrementRecord& last = s.solid.increments.back().record;
  s.section.set("analysis", "elastoplastic_static")
      .set("model", "solid_3d")
      .set("status", s.solid.status)
      .set("increments", static_cast<long>(s.solid.increments.size()) - 1)
      .set("max_plastic_strain", last.max_plastic_strain)
      .set("plastic_points", last.plastic_points)
      .set("seconds", s.solid.timer.total());
  s.status = s.solid.status, s.stop_reason = s.solid.stop_reason, s.timer = s.solid.timer;
  s.view = std::make_unique<SolidPreload>(preload, s.solid);
}

} // namespace

StagedOutcome run_staged(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                         io::OutputDirectory* out, const std::string& dir,
                         const io::Restart* restart) {
  StagedOutcome outcome;
  spec::ProblemSpec preload = spec.staged().stages[0];
  const spec::ProblemSpec& event = spec.staged().stages[1];
  const spec::StageLink& link = spec.staged().links[1];
  io::Summary summary({spec.name, spec.description, spec.units, "staged", ""});
  summary.set("mpi_ranks", session.size());
  PhaseTimer timer;

  log::info("stage ", preload.stage, ": ", preload.description);
  const auto alone = preload_alone(event, session);
  const solvers::PetscSession& preload_session = alone ? *alone : session;
  if (out) out->set_prefix(preload.stage + "_");
  SolvedPreload pre;
  if (preload.is_solid())
    solve_solid(pre, preload, session, preload_session, alone != nullptr, out);
  else
    solve_plane(pre, preload, session, preload_session, alone != nullptr, out);
  if (out) out->set_prefix("");
  timer.add_all(pre.timer, preload.stage + ".");
  if (session.size() > 1) pre.section.set("whole_on_every_rank", alone != nullptr);
  summary.section("stages").set(preload.stage, pre.section);
  if (pre.status != "completed") {
    outcome.status = "stopped";
    outcome.stop_reason = "stage " + preload.stage + ": " + pre.stop_reason;
    outcome.exit_code = 3;
  } else {
    log::info("stage ", event.stage, " from ", preload.stage);
    const explicit_dynamics::RunPlace place{out, dir, distribution::Ranks::of(session.comm()),
                                            &spec.settings, restart};
    ExplicitStage st = event.analysis == spec::Analysis::Sph
                           ? run_sph_stage(*pre.view, event, link, 1, place)
                           : run_pd_stage(*pre.view, event, link, 1, place);
    summary.section("checkpoints") = st.checkpoints.describe(st.timer.total());
    timer.add_all(st.timer, event.stage + ".");
    io::Json stage;
    stage.set("analysis", event.analysis == spec::Analysis::Sph ? "sph" : "peridynamics")
        .set("status", st.status)
        .set("counts", st.counts)
        .set("time_step", st.time_step)
        .set("results", st.results)
        .set("seconds", st.timer.total());
    summary.section("stages").set(event.stage, stage);
    summary.section("transfer") = st.transfer.json();
    if (out) st.history.write(*out);
    if (st.status != "completed") {
      outcome.status = st.status;
      outcome.stop_reason = "stage " + event.stage + ": " + st.stop_reason;
      outcome.exit_code = 1;
    }
  }
  summary.set_status(outcome.status, outcome.stop_reason);
  summary.set("openmp_threads", omp_get_max_threads()); // what the run ends with
  if (out) summary.write(*out, timer);
  return outcome;
}

} // namespace mf::stages
