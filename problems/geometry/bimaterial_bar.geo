// A bar of two parts bonded end to end, for problems/bimaterial_bar.yaml: the part `steel` over
// 0 <= x <= 10 and the part `aluminium` over 10 <= x <= 20, both 2 high. Units: mm.
// OpenCASCADE's fragments make the two rectangles share the curve x = 10, so that the body's
// boundary is the outer one and each part is one physical group of surfaces.
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 10, 2};
Rectangle(2) = {10, 0, 0, 10, 2};
BooleanFragments{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Physical Surface("steel") = {1};
Physical Surface("aluminium") = {2};
