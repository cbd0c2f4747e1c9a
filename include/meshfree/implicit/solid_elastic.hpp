#pragma once
// Linear elastic statics of a 3D meshfree body: K d = f assembled on the model with 3 DOFs a
// node and solved once; u^h at the nodes, each face condition's reaction or load, and the
// errors against an exact solution where the problem gives one.
#include "meshfree/core/timer.hpp"
#include "meshfree/implicit/solid_lines.hpp"
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/solvers/parallel.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace mf::implicit {

struct SolidElasticResult {
  PhaseTimer timer;
  SolidCounts counts;
  double matrix_nonzeros = 0.0;
  solvers::SolveReport solve;
  std::vector<double> parameters;   // the nodal parameters, 3 per node (every node)
  std::vector<Vec3> node_x, node_u; // nodes and u^h there
  std::vector<double> node_stress;  // the stress averaged at the nodes, 6 a node (rank 0)
  std::vector<Vec3> gauge_u;        // u^h at output.gauges
  std::vector<FaceReport> boundary;
  double error_l2 = std::numeric_limits<double>::quiet_NaN();     // relative, with an exact
  double error_energy = std::numeric_limits<double>::quiet_NaN(); // solution
  solvers::PeakMemory memory;
  std::shared_ptr<const SolidLineSampler> lines; // output.lines (rank 0's rows)
};

SolidElasticResult solve_solid_elastic(const spec::ProblemSpec& spec,
                                       const solvers::PetscSession& session);

/// summary.json, history.csv and fields.h5/.xmf (the nodes as points: u^h, the nodal
/// parameters, the stress averaged at the nodes and the exact displacement where there is one).
/// Rank 0 writes.
void write_solid_elastic_outputs(const spec::ProblemSpec& spec, const SolidElasticResult& r,
                                 const solvers::PetscSession& session, io::OutputDirectory& out);

} // namespace mf::implicit
