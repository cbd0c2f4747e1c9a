#pragma once
// The part of a problem file that belongs to a 3D Galerkin analysis (model solid_3d with
// elastic_static or elastoplastic_static): the prism's extent along z, the discretisation,
// conditions on named faces, the body force, load steps and solver controls. Plain data.
#include "meshfree/core/types.hpp"
#include "meshfree/geometry/prism.hpp"
#include "meshfree/spec/galerkin_spec.hpp"
#include "meshfree/spec/region_spec.hpp"
#include "meshfree/verification/exact_solutions_3d.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::spec {

/// A condition on faces of a 3D body (geometry::Prism's face names), optionally clipped to a box:
/// a displacement held by a penalty on the components with mask 1, a traction (force per area),
/// or a pressure (the traction -p n).
struct FaceCondition {
  std::string name;
  std::string key_path; // e.g. "boundary[0]", for messages
  std::vector<std::string> faces;
  std::optional<Box> box;
  bool constrains = false;
  Vec3 mask{0.0, 0.0, 0.0};
  Vec3 value{0.0, 0.0, 0.0};
  bool value_from_exact = false;
  double penalty = 0.0; // absolute alpha
  bool loads = false;
  Vec3 traction{0.0, 0.0, 0.0};
  bool traction_from_exact = false;
  bool pressure_load = false;
  double pressure = 0.0;
};

/// A segment of a 3D body sampled at `points` evenly spaced points (output.lines).
struct SolidLineSpec {
  std::string name;
  Vec3 from{0.0, 0.0, 0.0}, to{0.0, 0.0, 0.0};
  int points = 0;
};

/// Points of a named face, or of the body's section by a flat box (one extent zero), about
/// `spacing` apart (output.faces; geometry::face_sample_points, plane_sample_points).
struct SolidFaceSampleSpec {
  std::string name;
  std::string face;       // a face's name, or empty for
  std::optional<Box> box; // a flat box
  double spacing = 0.0;
};

/// elastic_static or elastoplastic_static with model solid_3d: the front's plane body extruded
/// from z0 by depth, meshfree nodes (the plane node cloud in layers along z), conditions on
/// faces, loaded in steps and solved by Newton's method and a linear solver with 3 DOFs a node.
struct SolidSpec {
  int material_index = 0;
  double z0 = 0.0, depth = 1.0;
  std::vector<geometry::Sphere> spheres; // spherical holes (geometry.spheres)
  DiscretisationSpec discretisation;
  std::vector<FaceCondition> boundary;
  Vec3 body_force{0.0, 0.0, 0.0}; // force per volume
  std::optional<verification::ExactSolution3D> exact;
  std::vector<LoadStep> steps;
  NonlinearSpec nonlinear;
  LinearSolverSpec linear_solver;
  std::vector<GaugeSpec> gauges;          // points whose displacement each increment records
  std::vector<SolidLineSpec> lines;       // sampled at the end (elastic) or each increment
  std::vector<SolidFaceSampleSpec> faces; // sampled as the lines are
  int fields_every = 1; // field frames every this many converged increments (and the last)
  // Set by a staged run, not read from the file: every increment's nodal parameters are kept
  // (IncrementRecord::parameters), on every rank, so a later stage can evaluate any increment.
  bool record_increment_parameters = false;

  bool samples() const { return !lines.empty() || !faces.empty(); }
  /// The body: `section` extruded from z0 by depth, minus the spheres.
  geometry::Prism body(const geometry::Domain& section) const {
    return geometry::Prism{section, z0, depth, spheres};
  }
};

} // namespace mf::spec
