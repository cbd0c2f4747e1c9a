#pragma once
// A plane body read from a geometry file (STEP, BRep, gmsh's .geo or .msh) through gmsh's API:
// the boundary of the file's surfaces as loops of named segments and arcs, a Domain like the
// built-in shapes (Domain::from_loops).
#include "meshfree/geometry/domain.hpp"
#include <optional>
#include <string>
#include <vector>

namespace mf::geometry {

/// A physical group of the file's surfaces: its name and the body they make.
struct FilePart {
  std::string name;
  Domain body;
};

/// A physical group of the file's curves: its name and its curves' pieces (each curve's in its
/// own sense), whether they bound the body or lie inside it (a crack drawn in the file).
struct FileCurve {
  std::string name;
  std::vector<Curve> pieces;
};

/// What a file holds: the body, its groups of surfaces (the parts a material may be given to) and
/// its groups of curves.
struct OutlineFile {
  Domain body;
  std::vector<FilePart> parts;
  std::vector<FileCurve> curves;
};

/// Reads the plane body of the file at `path`, its coordinates times `scale`. The boundary's
/// pieces are named after the physical group of curves that holds them (gmsh's name, else
/// "group<tag>"), or "curve<tag>" outside every group; lines become segments, curves whose points
/// lie on one circle arcs of at most a quarter turn (a hole that is a whole circle a circle hole),
/// other curves (splines, ellipses, a mesh's polylines) chords that turn at most 5 degrees. Error
/// where the file cannot be read, holds volumes or no surface, lies out of a plane z = const, or
/// makes more than one body (the whole file, or a group of its surfaces).
OutlineFile read_outline_file(const std::string& path, double scale);

/// The area of a body read from a file: its outline's less its holes', which lie inside it.
double file_body_area(const Domain& body);

/// A ring between two concentric circles.
struct Annulus {
  Vec2 center{0.0, 0.0};
  double inner = 0.0, outer = 0.0;
};
/// The ring a body is, where its outline is one whole circle (arcs about one centre, of one
/// radius, within 1e-9 of it) and its one hole a circle about the same centre: a tunnel's lining
/// drawn in a file, which particles fill in concentric rings as the built-in ring's.
std::optional<Annulus> annulus_of(const Domain& body);

} // namespace mf::geometry
