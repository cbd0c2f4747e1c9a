#pragma once
// What an elastoplastic analysis keeps of each converged increment: reactions and loads, the
// plastic zone, equilibrium, u^h at the monitors, and, when due, the nodal, Gauss-point and
// display-mesh fields and the line samples.
#include "meshfree/implicit/display_mesh.hpp"
#include "meshfree/implicit/elastoplastic_result.hpp"
#include "meshfree/implicit/elastoplastic_system.hpp"
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/io/checkpoint.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/solvers/nonlinear_system.hpp"
#include "meshfree/solvers/petsc_session.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <memory>
#include <utility>
#include <vector>

namespace mf::implicit {

class IncrementRecorder {
public:
  /// Shape functions at the nodes, monitors and line points (rank 0) and the field series
  /// (rank 0, when `out` is given), fixed for the run. Collective.
  IncrementRecorder(const spec::ProblemSpec& spec, const GalerkinModel& m,
                    const solvers::PetscSession& session, io::OutputDirectory* out);
  ~IncrementRecorder();

  /// Completes `rec` at the converged state (d, the committed states), writes the fields when
  /// asked, and appends it to r.increments (line samples to r.lines). Collective.
  void record(IncrementRecord rec, const std::vector<double>& d, const PointStates& st,
              const solvers::NonlinearBlockSystem& newton, bool write_fields,
              ElastoplasticResult& r);

  /// The increments from now on are on another model of the same body (a cloud refined during
  /// the analysis, with `spec` its discretisation): the shape tables are made anew and the field
  /// series go on on its points. `spec` and `m` must outlive the recorder. Collective.
  void move_to(const spec::ProblemSpec& spec, const GalerkinModel& m);

  /// Closes the field series.
  void close();

  /// The field series' state into a checkpoint (the steps so far split off into its parts), and
  /// back on a restart.
  void save(io::Checkpoints& checkpoints, const io::Saver& save);
  void restore(const io::Loader& load);

private:
  struct GaussOutput;
  /// The shape tables at the nodes, monitors and line points and the display mesh (rank 0), and
  /// the body load, of model m. Collective.
  void make_tables(const spec::ProblemSpec& spec, const GalerkinModel& m);
  const spec::ProblemSpec* spec_;
  const GalerkinModel* m_;
  const solvers::PetscSession& session_;
  bool writes_; // the fields are written (rank 0 with an output directory)
  ShapeTable node_table_, monitor_table_;
  std::vector<std::pair<const spec::LineSpec*, std::vector<Vec2>>> line_points_;
  std::vector<ShapeTable> line_tables_;
  std::unique_ptr<io::FieldOutput> fields_; // nodal fields (rank 0)
  std::vector<Vec2> node_u_, node_parameters_;
  std::vector<double> node_values_[7]; // stresses, szz, von Mises, alpha, plastic fraction
  std::unique_ptr<GaussOutput> gauss_;
  DisplayMesh display_mesh_;               // rank 0, when the fields are written
  std::unique_ptr<DisplaySeries> display_; // its series (rank 0)
  Vec2 body_load_{0.0, 0.0};               // gravity and body force over the body at factor 1
};

} // namespace mf::implicit
