#pragma once
// The segments of output.lines and the faces of output.faces of a 3D body, sampled as passive
// material points: u^h at each sample point, and the stress the body's J2 update gives from the
// point's own history carried through every converged state (as a staged run's particles are),
// so a line through the plastic zone shows the stress of the same law as the Gauss points,
// without a projection. Written as line_<name>.csv and face_<name>.csv, a row per sample point
// and state (a line's rows with their distance s from its start), and a face also as a point
// series for ParaView (face_<name>.h5/.xmf, a step per state).
#include "meshfree/implicit/solid_model.hpp"
#include "meshfree/io/output.hpp"
#include "meshfree/io/results.hpp"
#include "meshfree/materials/constitutive_model.hpp"
#include "meshfree/spec/problem_spec.hpp"
#include <string>
#include <utility>
#include <vector>

namespace mf::implicit {

/// Registers a 3D body's stress at its nodes (or its Gauss points) in a field series: stress_xx ..
/// stress_xy (Voigt order xx, yy, zz, yz, xz, xy), von_mises and, with 7 values a node,
/// plastic_strain, read from `values` (`stride` values a node) at each write.
void add_node_stress_fields(io::FieldOutput& fields, const std::vector<double>& values, int stride);

class SolidLineSampler {
public:
  /// The sample points of spec.solid().lines inside the body and of spec.solid().faces, with
  /// their shape functions.
  SolidLineSampler(const spec::ProblemSpec& spec, const SolidModel& m,
                   const materials::ConstitutiveModel& law);
  /// Carries every sample point to the converged state of nodal parameters `d` (all of them) and
  /// records its row, tagged `state` (the increment; 0 unloaded).
  void record(int state, const std::vector<double>& d);
  /// line_<name>.csv for each line, face_<name>.csv and the point series face_<name>.h5/.xmf
  /// (ParaView) for each face.
  void write(io::OutputDirectory& out) const;

private:
  struct Line {
    std::string file;  // line_<name> or face_<name>
    bool along = true; // rows hold s, the distance from `from`
    Vec3 from;
    std::vector<Vec3> x;
    SolidShapeTable table;
    std::vector<materials::MaterialState> committed;
    std::vector<std::vector<double>> rows;
  };
  materials::ConstitutiveModel law_;
  std::vector<Line> lines_;
  void add(Line l, const SolidModel& m);
};

} // namespace mf::implicit
