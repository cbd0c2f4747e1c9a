// A compound cylinder, a quarter of its section, for problems/compound_cylinder.yaml: the part
// `liner` over 10 <= r <= 15 and the part `jacket` over 15 <= r <= 20 (mm) about the origin, in
// the quadrant x, y >= 0, sharing the arc r = 15; the curves `bore` (r = 10) and `outside`
// (r = 20). gmsh's own kernel: quarter circles through their centre.
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {15, 0, 0};
Point(4) = {20, 0, 0};
Point(5) = {0, 10, 0};
Point(6) = {0, 15, 0};
Point(7) = {0, 20, 0};
Circle(1) = {2, 1, 5};
Circle(2) = {3, 1, 6};
Circle(3) = {4, 1, 7};
Line(4) = {2, 3};
Line(5) = {3, 4};
Line(6) = {6, 5};
Line(7) = {7, 6};
Curve Loop(1) = {4, 2, 6, -1};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 3, 7, -2};
Plane Surface(2) = {2};
Physical Surface("liner") = {1};
Physical Surface("jacket") = {2};
Physical Curve("bore") = {1};
Physical Curve("outside") = {3};
