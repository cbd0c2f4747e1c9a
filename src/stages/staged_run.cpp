#include "meshfree/stages/staged_run.hpp"
#include "meshfree/core/log.hpp"
#include "meshfree/implicit/elastoplastic_output.hpp"
#include "meshfree/implicit/elastoplastic_solve.hpp"
#include "meshfree/implicit/point_law.hpp"
#include "meshfree/stages/explicit_stage.hpp"
#include <cmath>
#include <limits>

namespace mf::stages {

io::Json TransferReport::json() const {
  io::Json j;
  j.set("particles", particles)
      .set("plastic_particles", plastic_particles)
      .set("max_displacement", max_u)
      .set("stored_elastic_energy", stored_energy);
  io::Json h;
  for (std::size_t k = 0; k < held.size(); ++k) h.set(std::to_string(k), held[k]);
  j.set("held", h);
  j.set("initial_out_of_balance", out_of_balance);
  if (peridynamic) {
    j.set("residual_at_galerkin_displacement", residual_at_uh)
        .set("equilibrium", relax_method)
        .set("relaxation_iterations", relax_iterations)
        .set("relaxation_linear_iterations", relax_linear_iterations)
        .set("relaxation_iterations_from_zero", relax_iterations_from_zero)
        .set("relaxation_residual_ratio", relax_residual)
        .set("relaxation_seconds", relax_seconds)
        .set("relaxation_seconds_from_zero", relax_seconds_from_zero)
        .set("pd_vs_galerkin_displacement", pd_vs_galerkin);
  } else {
    j.set("balanced_residual", balanced_residual)
        .set("particles_over_yield_surface", over_surface)
        .set("particles_returned_to_yield_surface", returned)
        .set("worst_yield_ratio", worst_yield_ratio)
        .set("density_mismatch", density_mismatch)
        .set("settle_time", settle_time)
        .set("settle_drift", settle_drift);
  }
  j.set("seconds", seconds);
  return j;
}

io::History take_rows(io::History& h) {
  io::History rows = std::move(h);
  h = io::History(rows.columns());
  return rows;
}

io::History staged_history(const io::History& preload, const io::History& run, int from, int index,
                           const std::vector<std::string>& gauges) {
  std::vector<std::string> columns = run.columns();
  columns.insert(columns.begin() + 1, "stage");
  io::History out(columns);
  const auto is_gauge = [&gauges](const std::string& c) {
    for (const auto& g : gauges)
      if (c.rfind(g + "_", 0) == 0) return true;
    return false;
  };
  std::vector<char> keep(run.columns().size());
  for (std::size_t c = 0; c < keep.size(); ++c) keep[c] = c == 0 || is_gauge(run.columns()[c]);
  for (const auto& row : preload.rows()) {
    std::vector<double> r{row[0], static_cast<double>(from)};
    for (std::size_t c = 1; c < row.size(); ++c)
      r.push_back(keep[c] ? row[c] : std::numeric_limits<double>::quiet_NaN());
    out.append_with_gaps(std::move(r));
  }
  for (const auto& row : run.rows()) {
    std::vector<double> r = row;
    r.insert(r.begin() + 1, static_cast<double>(index));
    out.append(std::move(r));
  }
  return out;
}

void begin_stage_history(ExplicitStage& st, const io::History& replay, io::History& run,
                         const std::vector<io::GaugeSpec>& gauges, int from, int index,
                         io::OutputDirectory* out) {
  std::vector<std::string> names;
  for (const auto& g : gauges) names.push_back(g.name);
  st.history = staged_history(replay, run, from, index, names);
  if (out) st.history.stream_to(*out);
  io::History* staged = &st.history;
  run.also_to([staged, index](const std::vector<double>& row) {
    std::vector<double> r = row;
    r.insert(r.begin() + 1, static_cast<double>(index));
    staged->append(std::move(r));
  });
}

void record_stage(ExplicitStage& st, const std::string& status, const std::string& stop_reason,
                  const PhaseTimer& timer) {
  st.status = status;
  st.stop_reason = stop_reason;
  st.timer = timer;
}

double stored_energy(const io::ProblemSpec& preload, const PreloadAtParticles& pa,
                     const std::vector<double>& volume) {
  // sigma : C^-1 sigma = [(s11^2 + s22^2 + s33^2) - 2 nu (s11 s22 + s22 s33 + s33 s11)
  //                       + 2 (1 + nu) (s23^2 + s13^2 + s12^2)] / E  (isotropic compliance).
  double w = 0.0;
  for (std::size_t i = 0; i < pa.image.size(); ++i) {
    const implicit::PointLaw law = implicit::point_law(preload, pa.image[i].x);
    const double nu = law.params.nu;
    const materials::Vec6& s = pa.final_stress()[i];
    const double normal = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] -
                          2.0 * nu * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]);
    const double shear = 2.0 * (1.0 + nu) * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    w += 0.5 * volume[i] * (normal + shear) / law.params.E;
  }
  return w;
}

StagedOutcome run_staged(const io::ProblemSpec& spec, const solvers::PetscSession& session,
                         io::OutputDirectory* out, const std::string& dir,
                         const io::Restart* restart) {
  StagedOutcome outcome;
  io::ProblemSpec preload = spec.stages[0];
  preload.record_increment_parameters = true; // each particle is carried through them
  const io::ProblemSpec& event = spec.stages[1];
  const io::StageLink& link = spec.links[1];
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
    const io::CheckpointPolicy& policy =
        event.analysis == io::Analysis::Sph ? event.sph->checkpoint : event.pd->checkpoint;
    const distribution::Ranks ranks = distribution::Ranks::of(session.comm());
    io::Checkpoints checkpoints(dir, ranks, policy, spec.settings, restart);
    const auto resume = restart ? restart->open(ranks.rank) : nullptr;
    const StageCheckpoints kept{&checkpoints, resume.get(), ranks};
    ExplicitStage st = event.analysis == io::Analysis::Sph
                           ? run_sph_stage(preload, pre, event, link, 1, out, kept)
                           : run_pd_stage(preload, pre, event, link, 1, out, kept);
    summary.section("checkpoints") = checkpoints.counts().describe(st.timer.total());
    timer.add_all(st.timer, event.stage + ".");
    io::Json stage;
    stage.set("analysis", event.analysis == io::Analysis::Sph ? "sph" : "peridynamics")
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
