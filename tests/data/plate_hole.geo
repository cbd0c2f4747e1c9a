// Quarter of a 10 x 10 plate with a central hole of radius 1: the square [0, 5]^2 without the
// disc r < 1 (the body of problems/plate_hole_kirsch.yaml). Exact area 25 - pi/4.
// Triangles by default; `-setnumber quads 1` gives 8-node serendipity quadrangles (Q8).
// The commands that made the committed meshes are in README.md beside this file.
DefineConstant[ quads = {0, Name "quads"} ];
lc_far = 0.6;
lc_hole = 0.2;
Point(1) = {0, 0, 0, lc_hole};
Point(2) = {1, 0, 0, lc_hole};
Point(3) = {5, 0, 0, lc_far};
Point(4) = {5, 5, 0, lc_far};
Point(5) = {0, 5, 0, lc_far};
Point(6) = {0, 1, 0, lc_hole};
Line(1) = {2, 3};       // bottom, y = 0
Line(2) = {3, 4};       // right, x = 5
Line(3) = {4, 5};       // top, y = 5
Line(4) = {5, 6};       // left, x = 0
Circle(5) = {6, 1, 2};  // the hole
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5};
Physical Surface("plate") = {1};
If (quads)
  Mesh.RecombineAll = 1;
  Mesh.Algorithm = 6;              // frontal-Delaunay (8, its quad variant, crashes gmsh 4.8.4)
  Mesh.RecombinationAlgorithm = 2; // simple full-quad: no triangles left
  Mesh.ElementOrder = 2;
  Mesh.SecondOrderIncomplete = 1;  // 8-node serendipity quadrangles (gmsh type 16)
EndIf
