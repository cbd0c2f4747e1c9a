#pragma once
// The boundary between meshfree and gmsh. gmsh's C++ API brings some 80 shared libraries
// (OpenCASCADE, FLTK, ...) whose loading would add a fifth of a second to the start of every
// run, so the meshing lives in a small shared library of its own (libmeshfree_gmsh.so, built
// from src/fem/gmsh_plugin.cpp), loaded only when a mesh is made. Plain data crosses the
// boundary, in both directions.
#include "meshfree/core/plugin.hpp"
#include <cstddef>
#include <string>
#include <vector>

namespace mf::fem::gmsh_mesher {

struct Request {
  std::vector<double> polygon; // x0, y0, x1, y1, ...: the outline, counter-clockwise
  // Where the outline has arcs (rounded corners): cx, cy of each of its pieces (from point i to
  // point i + 1), the centre of the arc it is or NaN, NaN for a straight one; empty: all straight.
  std::vector<double> polygon_centres;
  std::vector<double> holes;   // cx, cy, r of each hole
  // Polygon holes: their vertices x0, y0, x1, y1, ... one after another, and each one's count.
  std::vector<double> polygon_holes;
  std::vector<int> polygon_hole_sizes;
  // Where they have arcs: cx, cy of each of their pieces as polygon_centres; empty: all straight.
  std::vector<double> polygon_hole_centres;
  // Curves inside the body that the mesh follows (where parts meet): x0, y0, x1, y1, cx, cy of
  // each, the centre NaN, NaN for a straight one.
  std::vector<double> interfaces;
  std::vector<double> boxes;   // x0, y0, x1, y1, z0, z1, element size of each refinement box
  double size = 0.0;           // element size elsewhere
  // gmsh's type of the elements wanted: 2 (T3), 3 (Q4), 16 (Q8) of the plane body, or 4 (tet4),
  // 11 (tet10) of the prism that extrudes it from z = z0 by `depth` along z.
  int element_type = 3;
  double z0 = 0.0, depth = 0.0;
  std::vector<double> spheres; // cx, cy, cz, r of each spherical hole cut from the prism
};

struct Result {
  std::vector<std::size_t> node_tags;
  std::vector<double> xyz;                 // 3 per node, in node_tags' order
  std::vector<int> element_types;          // the element types made of the wanted dimension
  std::vector<std::size_t> element_counts; // how many of each
  std::vector<std::size_t> connectivity;   // node tags of the elements of element_types[0]
  std::string error;                       // gmsh's reason when it failed; empty otherwise
};

using Function = void (*)(const Request&, Result&);
inline constexpr const char* kEntry = "meshfree_gmsh_mesh";

} // namespace mf::fem::gmsh_mesher
