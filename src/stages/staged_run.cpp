#include "meshfree/stages/staged_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include <memory>

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

} // namespace

StagedOutcome run_staged(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                         io::OutputDirectory* out, const std::string& dir,
                         const io::Restart* restart) {
  StagedOutcome outcome;
  spec::ProblemSpec preload = spec.staged().stages[0];
  preload.galerkin().record_increment_parameters = true; // each particle is carried through them
  const spec::ProblemSpec& event = spec.staged().stages[1];
  const spec::StageLink& link = spec.staged().links[1];
  io::Summary summary({spec.name, spec.description, spec.units, "staged", ""});
  summary.set("mpi_ranks", session.size());
  PhaseTimer timer;

  log::info("stage ", preload.stage, ": ", preload.description);
  const auto alone = preload_alone(event, session);
  const solvers::PetscSession& preload_session = alone ? *alone : session;
  if (out) out->set_prefix(preload.stage + "_");
  implicit::ElastoplasticResult pre =
      implicit::solve_elastoplastic_static(preload, preload_session, out);
  if (alone) pre.memory = solvers::peak_memory(session.comm()); // every rank holds it whole
  if (out) implicit::write_elastoplastic_outputs(preload, pre, preload_session, *out);
  if (out) out->set_prefix("");
  timer.add_all(pre.timer, preload.stage + ".");
  const implicit::IncrementRecord& last = pre.increments.back();
  io::Json preload_section;
  preload_section.set("analysis", "elastoplastic_static")
      .set("status", pre.status)
      .set("increments", static_cast<long>(pre.increments.size()) - 1)
      .set("max_plastic_strain", last.max_plastic_strain)
      .set("plastic_points", last.plastic_points)
      .set("equilibrium_error", last.equilibrium_error)
      .set("seconds", pre.timer.total());
  if (session.size() > 1) preload_section.set("whole_on_every_rank", alone != nullptr);
  summary.section("stages").set(preload.stage, preload_section);
  if (pre.status != "completed") {
    outcome.status = "stopped";
    outcome.stop_reason = "stage " + preload.stage + ": " + pre.stop_reason;
    outcome.exit_code = 3;
  } else {
    log::info("stage ", event.stage, " from ", preload.stage);
    const explicit_dynamics::RunPlace place{out, dir, distribution::Ranks::of(session.comm()),
                                            &spec.settings, restart};
    ExplicitStage st = event.analysis == spec::Analysis::Sph
                           ? run_sph_stage(preload, pre, event, link, 1, place)
                           : run_pd_stage(preload, pre, event, link, 1, place);
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
  if (out) summary.write(*out, timer);
  return outcome;
}

} // namespace mf::stages
