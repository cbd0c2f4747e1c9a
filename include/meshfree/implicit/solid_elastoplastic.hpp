#pragma once
// Quasi-static elastoplastic analysis of a 3D meshfree body: the load schedule of the problem
// (implicit/load_stepping, with cut-back) over SolidElastoplasticSystem, Newton through PETSc
// SNES with 3 DOFs a node; each converged increment's factors, face reactions and loads, Newton
// counts and plastic points, and at the end u^h at the nodes and the Gauss points' stress and
// equivalent plastic strain.
#include "meshfree/core/timer.hpp"
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/implicit/solid_forms.hpp"
#include "meshfree/implicit/solid_lines.hpp"
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <memory>
#include <string>
#include <vector>

namespace mf::implicit {

struct SolidIncrement {
  IncrementRecord record; // step, factors, Newton report, cut-backs, plastic points
  std::vector<FaceReport> faces;
  std::vector<Vec3> gauges; // u^h at the problem's gauges
};

struct SolidElastoplasticResult {
  PhaseTimer timer;
  std::string status = "completed", stop_reason;
  SolidCounts counts;
  std::string solver;
  std::vector<SolidIncrement> increments; // [0]: the unloaded state
  std::vector<double> parameters;         // the last converged state, 3 per node
  std::vector<Vec3> node_x, node_u;
  solvers::PeakMemory memory;
  // The model the parameters belong to (its nodes' shape functions evaluate u^h anywhere) and
  // the material's J2 parameters; each increment's parameters are in its record with
  // SolidSpec::record_increment_parameters.
  std::shared_ptr<const SolidModel> model;
  materials::ConstitutiveModel material;
  std::shared_ptr<const SolidLineSampler> lines; // output.lines at every state (rank 0's rows)
};

/// Writes the field series as it goes into `out` (rank 0's folder; null elsewhere, or for no
/// output): fields.h5/.xmf (u^h at the nodes) and gauss_points.h5/.xmf (stress, von Mises,
/// equivalent plastic strain) at the unloaded state and every increment the schedule marks
/// (output.fields_every, and each step's last), at time step + step fraction.
SolidElastoplasticResult solve_solid_elastoplastic(const spec::ProblemSpec& spec,
                                                   const solvers::PetscSession& session,
                                                   io::OutputDirectory* out = nullptr);

/// summary.json and history.csv (a row per converged increment). Rank 0 writes.
void write_solid_elastoplastic_outputs(const spec::ProblemSpec& spec,
                                       const SolidElastoplasticResult& r,
                                       const solvers::PetscSession& session,
                                       io::OutputDirectory& out);

} // namespace mf::implicit
