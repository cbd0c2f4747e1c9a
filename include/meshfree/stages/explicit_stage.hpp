#pragma once
// The explicit stage of a staged run, started from the preload: its particles are built from the
// stage's own spec, take the preload's state (sample_preload) and its held conditions
// (held_conditions), are settled (SPH, optional) or relaxed to their own equilibrium
// (peridynamics, adaptive dynamic relaxation), and then run to the stage's end time. The
// preload's increments are replayed on the particles first, at pseudo-times -1..0, so that the
// history and the field series of the particles cover the whole run.
#include "meshfree/core/timer.hpp"
#include "meshfree/explicit/run_driver.hpp"
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/particles/particle_set.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include "meshfree/stages/preload.hpp"
#include "meshfree/stages/preload_sampling.hpp"
#include "meshfree/stages/transfer_report.hpp"
#include <string>
#include <vector>

namespace mf::stages {

struct ExplicitStage {
  io::History history; // "time", "stage" (the index of the stage in `stages:`), the run's columns
  TransferReport transfer;
  std::string status = "completed", stop_reason;
  io::Json counts, time_step, results;
  PhaseTimer timer;
  io::CheckpointCounts checkpoints; // what the stage's checkpoints cost
  // The owned particles at the end: reference positions and displacements (3 per particle), and
  // for SPH the stress (3D Voigt, tension positive) and equivalent plastic strain.
  std::vector<double> position, displacement;
  std::vector<materials::Vec6> stress;
  std::vector<double> plastic_strain;
};

/// The stage is run at `place` (explicit_dynamics::RunPlace): its output folder, checkpoints and
/// the checkpoint it restarts from (after the preload has been run again and replayed), and the
/// ranks it is spread over (the transfer is made on the whole body on every rank, then the body
/// is split as a standalone run's is).
ExplicitStage run_pd_stage(const Preload& preload, const spec::ProblemSpec& stage,
                           const spec::StageLink& link, int index,
                           const explicit_dynamics::RunPlace& place = {});
ExplicitStage run_sph_stage(const Preload& preload, const spec::ProblemSpec& stage,
                            const spec::StageLink& link, int index,
                            const explicit_dynamics::RunPlace& place = {});

/// One history of the rows of the replayed preload (stage `from`) and of the run (stage `index`),
/// with a "stage" column after "time". Of the preload's rows only time and the gauge columns
/// (named "<gauge>_...") are kept; the rest (energies, rates) belong to the explicit run and are
/// NaN there.
io::History staged_history(const io::History& preload, const io::History& run, int from, int index,
                           const std::vector<std::string>& gauges);

/// Starts the stage's history: the replayed preload's rows (staged_history), to which every row
/// the run's history records from now on is added as it comes.
void begin_stage_history(ExplicitStage& st, const io::History& replay, io::History& run,
                         const std::vector<spec::GaugeSpec>& gauges, int from, int index);

/// The stage's status and timer.
void record_stage(ExplicitStage& st, const std::string& status, const std::string& stop_reason,
                  const PhaseTimer& timer);

/// Moves the rows recorded so far out of `h` (leaving its columns): the replayed preload's rows
/// are kept apart from the run's, whose summaries they must not enter.
io::History take_rows(io::History& h);

/// The elastic strain energy of the preload's final stress at the particles, each of reference
/// volume V with the elasticity of the preload's material there: sum V sigma : C^-1 sigma / 2.
/// The small-strain energy is an integral over the reference body, so the reference volume, not
/// the preloaded one m / rho.
double stored_energy(const Preload& preload, const PreloadAtParticles& pa,
                     const std::vector<double>& volume);

/// The reference positions of the first n particles of P.
std::vector<Vec3> reference_positions(const particles::ParticleSet& P, int n);

/// What the transfer report says of the preload at the particles alone: how many particles, how
/// many of them plastic, the largest displacement and the stored energy (particles of reference
/// volume `volume`).
void describe_preload(TransferReport& t, const Preload& preload, const PreloadAtParticles& pa,
                      const std::vector<double>& volume);

/// "(x, y)" of a plane preload's vector, "(x, y, z)" of a 3D one's, for the log.
std::string vector_text(const Vec3& v, const Preload& preload);

} // namespace mf::stages
