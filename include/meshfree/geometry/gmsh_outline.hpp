#pragma once
// The boundary between meshfree and gmsh's reader of geometry files (libmeshfree_gmsh.so, loaded
// only when a body is read from a file: see fem/gmsh_mesher.hpp for why). Plain data crosses it.
#include "meshfree/geometry/domain.hpp"
#include <string>
#include <vector>

namespace mf::geometry::gmsh_outline {

struct Request {
  std::string path;   // a .step, .stp, .brep, .geo or .msh file
  double scale = 1.0; // every coordinate of the file times this
};

/// A named group of the file's entities (gmsh's physical groups): its dimension and name (gmsh's
/// name, or "group<tag>" where it has none); of a group of surfaces, the boundary of their union;
/// of a group of curves, each curve's pieces (a crack drawn in the file).
struct Group {
  int dimension = 0;
  std::string name;
  std::vector<std::vector<Curve>> loops;
};

struct Result {
  int dimension = 0;                     // the highest dimension of the file's entities
  std::vector<std::vector<Curve>> loops; // the boundary of its surfaces, each loop closed
  std::vector<Group> groups;
  std::string error; // why the file cannot be read; empty otherwise
};

using Function = void (*)(const Request&, Result&);
inline constexpr const char* kEntry = "meshfree_gmsh_read_outline";

} // namespace mf::geometry::gmsh_outline
