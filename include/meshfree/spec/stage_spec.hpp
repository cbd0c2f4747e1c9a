#pragma once
// How a stage of a staged run (analysis: staged) starts from the state of an earlier stage: which
// stage, which of its conditions stay on (held) and which are taken off (released), the mirror
// planes that complete a symmetric part, and the settling (SPH) or relaxation (peridynamics) of
// the transferred state. Plain data.
#include <string>
#include <vector>

namespace mf::spec {

/// A plane x_axis = at across which a preload computed on a symmetric part is mirrored to give
/// the whole body of the next stage.
struct MirrorPlane {
  int axis = 0;
  double at = 0.0;
};

struct StageLink {
  std::string key_path; // "stages[k]", for messages
  int from = -1;        // the stage whose state this one starts from (-1: none)
  std::vector<std::string> hold, release;
  std::vector<MirrorPlane> mirror;
  // SPH: a settle phase with mass-proportional damping before t = 0 (time 0: none), and the
  // radial return of particles found outside their yield surface.
  double settle_time = 0.0, settle_damping = 0.0;
  bool return_to_surface = false;
  // Peridynamics: the body's own equilibrium from u^h, by Newton's method on the linearised bond
  // stiffness (pd::solve_statics) or by adaptive dynamic relaxation (pd::relax), and whether to
  // reach it from u = 0 as well, to count the iterations the preload saves.
  // equilibrium_given: the file chose one (a 3D body relaxes by ADR; newton is refused there).
  bool implicit_equilibrium = true, equilibrium_given = false;
  double relax_tolerance = 1e-6;
  int relax_max_iterations = 200000;
  bool relax_from_zero = true;
};

} // namespace mf::spec
