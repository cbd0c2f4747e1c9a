// The half stepped bar of problems/filleted_bar.yaml as a gmsh geometry file, its boundary curves
// in physical groups named as the problem's edges: the shoulder's fillet of radius 1 is the
// circular arc from (11, 2.5) to (10, 3.5) about (11, 3.5). Units: mm. OpenCASCADE's kernel, so
// that gmsh writes the same body as STEP and BRep (scripts/make_geometry_files.sh):
// filleted_bar.step, read by problems/filleted_bar_from_step.yaml.
SetFactory("OpenCASCADE");
Point(1) = {0, 0, 0};
Point(2) = {20, 0, 0};
Point(3) = {20, 2.5, 0};
Point(4) = {11, 2.5, 0};
Point(5) = {11, 3.5, 0}; // the fillet's centre
Point(6) = {10, 3.5, 0};
Point(7) = {10, 5, 0};
Point(8) = {0, 5, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Circle(4) = {4, 5, 6};
Line(5) = {6, 7};
Line(6) = {7, 8};
Line(7) = {8, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Physical Curve("symmetry") = {1};
Physical Curve("right") = {2};
Physical Curve("narrow_top") = {3};
Physical Curve("fillet") = {4};
Physical Curve("shoulder") = {5};
Physical Curve("top") = {6};
Physical Curve("left") = {7};
Physical Surface("bar") = {1};
