#pragma once
// A triangle mesh of the body on which ParaView shows an implicit solution as filled contours
// and, through Warp By Vector with `displacement`, as the deformed shape: meshfree nodes and
// Gauss points are point clouds, which show neither.
// - Meshfree models: the body meshed into linear triangles at the node spacing as a T3
//   finite-element run would mesh it (read_fe_mesh: a structured grid on a plain rectangle,
//   gmsh with the refinement boxes otherwise); u^h at a vertex is the RK/MLS approximation with
//   the nodal parameters, sum_I phi_I(x) d_I.
// - Finite-element models: their own mesh, each quadrilateral split into triangles (Q8 through
//   its mid-side nodes); the vertices are the nodes and u^h their nodal values.
// Stresses and the equivalent plastic strain come from the Gauss points in two steps: the
// nodal average (nodal_average: weights phi_I(x_g)^2 w_g), then the model's shape functions
// at the vertex, sum_I phi_I(x) s_I ([Hinton & Campbell 1974] smoothing). Both steps keep a
// uniform field exactly (positive weights normalised to one, then a partition of unity).
#include "meshfree/implicit/galerkin_model.hpp"
#include "meshfree/implicit/meshfree_space.hpp"
#include "meshfree/implicit/nodal_average.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <memory>
#include <utility>
#include <vector>

namespace mf::implicit {

struct DisplayMesh {
  std::vector<Vec2> x; // vertices
  io::GridCells cells; // triangles
  ShapeTable table;    // the model's shape functions at the vertices (values)
};

/// The display mesh of the model (on the calling rank: gmsh and the shape functions).
DisplayMesh display_mesh(const spec::ProblemSpec& spec, const GalerkinModel& m);

/// Fields at the vertices of a display mesh.
struct DisplayFields {
  static constexpr int kScalars = 6;
  static const char* const kNames[kScalars]; // stress_xx, yy, xy, zz, von_mises, plastic_strain
  std::vector<Vec2> u;
  std::vector<double> values[kScalars];
};

/// u^h from the nodal parameters d (all of them) and the nodal averages at the vertices.
DisplayFields display_fields(const DisplayMesh& mesh, const std::vector<double>& d,
                             const NodalAverage& avg);

/// The display mesh of an elastic solution d (all nodal parameters) with its fields, on rank 0
/// (empty elsewhere): the Gauss-point stresses C eps(u^h) averaged as above. Collective.
std::pair<DisplayMesh, DisplayFields> elastic_display(const spec::ProblemSpec& spec,
                                                      const GalerkinModel& m,
                                                      const std::vector<double>& d,
                                                      const solvers::PetscSession& session);

/// The series `display_mesh` (display_mesh.h5/.xmf): one grid of triangles per write.
class DisplaySeries {
public:
  /// `out` null: nothing is written (ranks other than 0).
  DisplaySeries(io::OutputDirectory* out, const DisplayMesh& mesh);
  void write(double time, DisplayFields fields);
  /// The writes from now on are on another mesh (an adapted cloud's).
  void regrid(const DisplayMesh& mesh) { output_.regrid(mesh.x, mesh.cells); }
  io::FieldOutput& output() { return output_; }
  void close() { output_.close(); }

private:
  DisplayFields fields_;
  io::FieldOutput output_;
};

} // namespace mf::implicit
