#include "meshfree/stages/staged_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/stages/explicit_stage.hpp"

namespace mf::stages {

StagedOutcome run_staged(const spec::ProblemSpec& spec, const solvers::PetscSession& session,
                         io::OutputDirectory* out, const std::string& dir,
                         const io::Restart* restart) {
  StagedOutcome outcome;
  spec::ProblemSpec preload = spec.staged().stages[0];
  preload.galerkin().record_increment_parameters = true; // each particle is carried through them
  const spec::ProblemSpec& event = spec.staged().stages[1];
  const spec::StageLink& link = spec.staged().links[1];
  io::Summary summary({spec.name, spec.description, spec.units, "staged", ""});
  PhaseTimer timer;

  log::info("stage ", preload.stage, ": ", preload.description);
  if (out) out->set_prefix(preload.stage + "_");
  implicit::ElastoplasticResult pre = implicit::solve_elastoplastic_static(preload, session, out);
  if (out) implicit::write_elastoplastic_outputs(preload, pre, session, *out);
  if (out) out->set_prefix("");
  timer.add_all(pre.timer, preload.stage + ".");
  const implicit::IncrementRecord& last = pre.increments.back();
  summary.section("stages").set(preload.stage,
                                io::Json()
                                    .set("analysis", "elastoplastic_static")
                                    .set("status", pre.status)
                                    .set("increments", static_cast<long>(pre.increments.size()) - 1)
                                    .set("max_plastic_strain", last.max_plastic_strain)
                                    .set("plastic_points", last.plastic_points)
                                    .set("equilibrium_error", last.equilibrium_error)
                                    .set("seconds", pre.timer.total()));
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
