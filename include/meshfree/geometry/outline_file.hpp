#pragma once
// A plane body read from a geometry file (STEP, BRep, gmsh's .geo or .msh) through gmsh's API:
// the boundary of the file's surfaces as loops of named segments and arcs, a Domain like the
// built-in shapes (Domain::from_loops).
#include "meshfree/geometry/domain.hpp"
#include <string>
#include <vector>

namespace mf::geometry {

/// What a file holds: the body, and the names of its groups of curves and of surfaces.
struct OutlineFile {
  Domain body;
  std::vector<std::string> curve_groups, surface_groups;
};

/// Reads the plane body of the file at `path`, its coordinates times `scale`. The boundary's
/// pieces are named after the physical group of curves that holds them (gmsh's name, else
/// "group<tag>"), or "curve<tag>" outside every group; lines become segments, circles arcs of
/// at most a half turn, other curves (splines, ellipses) chords of at most a 200th of the body's
/// size. Error where the file cannot be read, holds volumes or no surface, lies out of a plane
/// z = const, or makes more than one body.
OutlineFile read_outline_file(const std::string& path, double scale);

} // namespace mf::geometry
