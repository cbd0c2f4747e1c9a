#pragma once
// Finite-element meshes made from a problem's own geometry with gmsh's C++ API (Geuzaine &
// Remacle 2009; gmsh reference manual, "Gmsh application programming interface"): the polygon
// minus its circular holes as an OpenCASCADE surface, or that surface extruded along z into a
// prism, minus spherical holes, meshed with tetrahedra; refinement boxes as size fields.
#include "meshfree/fem/mesh.hpp"
#include "meshfree/fem/tetrahedra.hpp"
#include "meshfree/geometry/domain.hpp"
#include "meshfree/geometry/node_generation.hpp"
#include "meshfree/geometry/prism.hpp"
#include <vector>

namespace mf::fem {

/// Meshes the body with elements of size `size`, `refinement[i].spacing` inside the i-th box
/// (the size grows linearly back to `size` over one `size` outside the box).
/// - T3: Frontal-Delaunay triangles;
/// - Q4: the triangles recombined into quadrilaterals (Blossom, full-quad);
/// - Q8: those quadrilaterals made second order, serendipity (no centre node), with the mid-side
///   nodes of boundary edges placed on the geometry (on the arc of a hole).
/// The result is oriented counter-clockwise and its nodes used by some element. Error with gmsh's
/// reason if gmsh cannot mesh the body, or if recombination leaves a triangle.
Mesh mesh_domain(const geometry::Domain& domain, double size,
                 const std::vector<geometry::Refinement>& refinement, ElementType type);

/// Meshes the prism (its section extruded from z0 by its depth along z, minus its spheres'
/// balls: OpenCASCADE's boolean cut) with Delaunay tetrahedra of size `size`
/// (`refinement[i].spacing` inside the i-th box, over its range of the depth): 4-node, or 10-node
/// ones whose mid-edge nodes on the boundary lie on the geometry (on the cylinder of a hole, on
/// a sphere). Nodes numbered in the order the elements name them, every element positively
/// oriented. Error with gmsh's reason if gmsh cannot mesh the body.
TetMesh mesh_prism(const geometry::Prism& body, double size,
                   const std::vector<geometry::Refinement>& refinement, bool quadratic);
/// The prism without spheres: `domain` extruded from z0 by `depth`.
TetMesh mesh_prism(const geometry::Domain& domain, double z0, double depth, double size,
                   const std::vector<geometry::Refinement>& refinement, bool quadratic);

} // namespace mf::fem
